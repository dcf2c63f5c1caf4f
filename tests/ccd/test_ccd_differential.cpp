// Seeded random and degenerate differential tests: the fast CCD and every filter against the exact rational reference.
// Zero false negatives is the requirement; at thickness 0 the fast path must even agree exactly (it falls back to the
// reference whenever floating point is unsure).
#include <cmath>
#include <random>

#include "ccd/ccd_test_support.hpp"
#include "ccd/exact_reference.hpp"
#include "ccd/pinned_segment_contact.hpp"

using clothcd::PairKind;
using clothcd::test::exact_contact_time_of;
using clothcd::test::make_query;
using clothcd::test::Vector3d;
namespace ccd = clothcd::ccd;

namespace {

// Generators of queries with a meaningful share of collisions: half are built around a contact at a random time, the
// rest are random or nearly touching.
class QueryGenerator {
 public:
  explicit QueryGenerator(unsigned seed) : random_(seed) {}

  // Continuous coordinates: contacts built at t* are only approximately exact after rounding, which is the point.
  ccd::CcdQuery random_query(PairKind kind) {
    std::array<Vector3d, 4> at_contact;
    for (Vector3d& p : at_contact) p = vector(1.0);
    if (coin()) {
      // Put the first primitive onto the second at a random time: vertex on the face, or edge a through a point of b.
      const double u = uniform(0, 1), v = uniform(0, 1 - u);
      if (kind == PairKind::VertexFace) {
        at_contact[0] = (1 - u - v) * at_contact[1] + u * at_contact[2] + v * at_contact[3];
      } else {
        const Vector3d on_b = (1 - u) * at_contact[2] + u * at_contact[3];
        at_contact[1] = on_b + (on_b - at_contact[0]) * uniform(0.1, 2.0);
      }
    }
    const double t_star = uniform(0, 1);
    ccd::CcdQuery query;
    query.kind = kind;
    for (int i = 0; i < 4; ++i) {
      const Vector3d velocity = vector(2.0);
      query.start[i] = at_contact[i] - t_star * velocity;
      query.end[i] = query.start[i] + velocity;
    }
    if (coin() && coin()) nudge(query, 1e-12);
    return query;
  }

  // Primitives that touch exactly at the step's end (at_start: its start), from continuous positions at the other end:
  // all four points meeting in one grid point (a collapsing cloth), or grid points with the vertex on a face's edge or
  // corner, or the edges crossing at their midpoints.
  ccd::CcdQuery touching_end_query(PairKind kind, bool at_start) {
    ccd::CcdQuery query;
    query.kind = kind;
    for (int i = 0; i < 4; ++i) {
      query.start[i] = vector(1.0);
      query.end[i] = grid_vector();
    }
    if (coin()) {
      for (int i = 1; i < 4; ++i) query.end[i] = query.end[0];
    } else if (kind == PairKind::VertexFace) {
      query.end[0] = coin() ? query.end[1 + pick(3)] : 0.5 * (query.end[1] + query.end[2]);
    } else {
      query.end[1] = query.end[2] + query.end[3] - query.end[0];
    }
    if (at_start) std::swap(query.start, query.end);
    return query;
  }

  // Primitives that share a coordinate plane for the whole step (a vertex and a face's edge, an edge's end and an
  // edge: equal coordinates on one axis at both ends), the other points to one side of it, with a contact in the plane
  // near a random time half of the time; or (crossed) two edges each with one end in a plane the other edge's other
  // end shares, so that the points off the plane lie on both sides of it.
  ccd::CcdQuery pinned_query(PairKind kind, bool crossed) {
    ccd::CcdQuery query;
    query.kind = kind;
    for (int i = 0; i < 4; ++i) {
      query.start[i] = vector(1.0);
      query.end[i] = query.start[i] + vector(0.5);
    }
    const int axis = pick(3);
    if (kind == PairKind::EdgeEdge && crossed) {
      for (auto* x : {&query.start, &query.end}) {
        (*x)[2][axis] = (*x)[0][axis];
        (*x)[3][axis] = (*x)[1][axis];
      }
      return query;
    }
    // Vertex-face: the vertex and the face's first edge; edge-edge: a's first end and edge b.
    const std::array<int, 3> on_plane = kind == PairKind::VertexFace ? std::array<int, 3>{0, 1, 2}
                                                                      : std::array<int, 3>{0, 2, 3};
    const int off_plane = kind == PairKind::VertexFace ? 3 : 1;
    if (coin()) {  // the first point passes through the segment of the other two at t*
      const double t_star = uniform(0, 1), lambda = uniform(0, 1);
      const Vector3d velocity = vector(1.0);
      const Vector3d p = query.start[on_plane[1]] + t_star * (query.end[on_plane[1]] - query.start[on_plane[1]]);
      const Vector3d q = query.start[on_plane[2]] + t_star * (query.end[on_plane[2]] - query.start[on_plane[2]]);
      query.start[on_plane[0]] = (1 - lambda) * p + lambda * q - t_star * velocity;
      query.end[on_plane[0]] = query.start[on_plane[0]] + velocity;
    }
    for (auto* x : {&query.start, &query.end}) {
      const double plane = (*x)[on_plane[1]][axis];
      for (const int i : on_plane) (*x)[i][axis] = plane;
      (*x)[off_plane][axis] = plane + uniform(0.1, 1.0);
    }
    return query;
  }

  // Coordinates on a coarse dyadic grid: exact coplanarity, coincident points, parallel and zero-length edges,
  // zero-area faces, contacts at exactly t = 0, 1/2 or 1, and planar motion (D identically zero).
  ccd::CcdQuery degenerate_query(PairKind kind) {
    ccd::CcdQuery query;
    query.kind = kind;
    const bool planar = coin();
    for (int i = 0; i < 4; ++i) {
      query.start[i] = grid_vector();
      query.end[i] = coin() ? query.start[i] : grid_vector();
      if (planar) query.start[i].z() = query.end[i].z() = 0.0;
    }
    if (coin()) query.end[pick(4)] = query.end[pick(4)];      // coincident points at the end
    if (coin()) query.start[pick(4)] = query.start[pick(4)];  // ... or at the start
    if (kind == PairKind::EdgeEdge && coin()) {               // parallel edges
      const Vector3d direction = grid_vector();
      query.start[3] = query.start[2] + direction;
      query.end[3] = query.end[2] + direction;
      query.start[1] = query.start[0] + 0.5 * direction;
      query.end[1] = query.end[0] + 0.5 * direction;
    }
    return query;
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
  bool coin() { return std::bernoulli_distribution(0.5)(random_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  Vector3d vector(double extent) {
    return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
  }
  Vector3d grid_vector() {
    std::uniform_int_distribution<int> step(-2, 2);
    return Vector3d(step(random_), step(random_), step(random_)) * 0.5;
  }
  void nudge(ccd::CcdQuery& query, double size) {
    auto& points = coin() ? query.start : query.end;
    points[pick(4)][pick(3)] += coin() ? size : -size;
  }

  std::mt19937 random_;
};

struct Tally {
  int queries = 0;
  int reference_hits = 0;
};

void check_against_reference(const ccd::CcdQuery& query, Tally& tally) {
  const bool expected = ccd::exact_collision_reference(query);
  ++tally.queries;
  tally.reference_hits += expected ? 1 : 0;
  const ccd::CcdResult result = ccd::continuous_collision(query, clothcd::test::exact_settings());
  INFO("start " << query.start[0].transpose() << " | " << query.start[1].transpose() << " | "
                << query.start[2].transpose() << " | " << query.start[3].transpose());
  INFO("end   " << query.end[0].transpose() << " | " << query.end[1].transpose() << " | " << query.end[2].transpose()
                << " | " << query.end[3].transpose());
  REQUIRE((result.hit || !expected));  // never a false negative
  CHECK(result.hit == expected);       // exact at thickness 0
  if (result.hit) {
    CHECK(result.toi >= 0.0);
    CHECK(result.toi <= 1.0);
  }
  clothcd::test::check_conservative_answer(query, result);
  if (expected) {
    CHECK_FALSE(ccd::nonpenetration_filter_culls(query));
    CHECK_FALSE(ccd::projection_filter_culls(query));
    CHECK_FALSE(ccd::projection_filter_culls(query, {}, ccd::ProjectionFilterOptions{true}));
    CHECK_FALSE(ccd::combined_filters_cull(query));
  }
}

}  // namespace

TEST_CASE("random queries: fast CCD and filters never miss a reference collision", "[ccd][differential]") {
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 20261122u : 4242u);
  Tally tally;
  for (int i = 0; i < 300; ++i) check_against_reference(generator.random_query(kind), tally);
  // The generator must produce a meaningful share of both answers, or the test proves nothing.
  CHECK(tally.reference_hits > tally.queries / 5);
  CHECK(tally.reference_hits < tally.queries * 4 / 5);
}

TEST_CASE("the time of impact is a lower bound of the earliest contact", "[ccd][differential]") {
  // The motion over [0, below], below the double just under toi, must be collision-free by the exact reference (the
  // end positions start + below (end - start) taken exactly as rationals).
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 8101u : 8102u);
  const bool decide_exactly = GENERATE(false, true);
  ccd::CcdSettings settings;
  settings.decide_exactly = decide_exactly;
  int checked = 0, conservative = 0;
  for (int i = 0; i < 300; ++i) {
    const ccd::CcdQuery query = i % 4 == 3 ? generator.degenerate_query(kind) : generator.random_query(kind);
    const ccd::CcdResult result = ccd::continuous_collision(query, settings);
    if (!result.hit || !(result.toi > 0.0)) continue;
    ++checked;
    conservative += result.state == ccd::CcdState::ConservativeHit ? 1 : 0;
    const mpq_class below(std::nextafter(result.toi, 0.0));
    ccd::exact::RationalPoints points;
    for (int p = 0; p < 4; ++p) {
      for (int d = 0; d < 3; ++d) {
        points[p][d] = mpq_class(query.start[p][d]);
        points[p + 4][d] = points[p][d] + below * (mpq_class(query.end[p][d]) - points[p][d]);
      }
    }
    INFO("query " << i << " toi " << result.toi);
    CHECK_FALSE(ccd::exact::exact_collision(kind, points).hit);
  }
  CHECK(checked > 50);
  if (!decide_exactly) CHECK(conservative > 0);  // the conservative hits' toi is checked too
}

TEST_CASE("a proven hit's time of impact is within 1e-6 below the exact earliest contact", "[ccd][differential]") {
  // The exact earliest contact time, narrowed by the rational reference to 2^-40, must not lie before toi (never late)
  // nor more than 1e-6 after it (tight); random, degenerate (contacts at t = 0 and 1, parallel edges, coplanar motion)
  // and nearly touching queries.
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 9101u : 9102u);
  int hits = 0, degenerate_hits = 0;
  for (int i = 0; i < 400; ++i) {
    const bool degenerate = i % 3 == 2;
    const ccd::CcdQuery query = degenerate ? generator.degenerate_query(kind) : generator.random_query(kind);
    const ccd::CcdResult result = ccd::continuous_collision(query);
    const ccd::exact::ContactTimeBounds exact = exact_contact_time_of(query);
    INFO("query " << i << " toi " << result.toi << " exact in [" << exact.lo << ", " << exact.hi << "]");
    REQUIRE(result.hit == exact.hit);
    if (!result.hit) continue;
    CHECK(result.state == ccd::CcdState::Hit);
    CHECK(result.toi <= exact.hi);
    CHECK(result.toi >= exact.lo - 1e-6);
    ++hits;
    degenerate_hits += degenerate ? 1 : 0;
  }
  CHECK(hits > 100);
  CHECK(degenerate_hits > 20);
}

TEST_CASE("a time of impact past a near touch of the coplanarity cubic is the later real contact's",
          "[ccd][differential]") {
  // A vertex at the origin and a face whose plane comes within about 1e-15 of it at t = 0.57 (D has a complex pair of
  // roots 1.5e-7 from the real axis there: no contact) and passes through it at t = 0.61, in the same piece of the
  // step, the vertex inside the face throughout (in the xy projection). Bracketing D's first root by halving follows the near touch, where no interval
  // sign is certain; only a bracket with certain opposite signs of D at its ends may give the time of impact.
  const std::array<Vector3d, 4> start{Vector3d(0, 0, 0), Vector3d(-1, -0.0, 0x1.1ca81054e1da0p+3),
                                      Vector3d(1, -1, -0x1.197c481a4b052p+4), Vector3d(1, 1, -0.0)};
  const std::array<Vector3d, 4> end{Vector3d(0, 0, 0), Vector3d(-1, -0.5, 0x1.232bc83a96d4ep+3),
                                    Vector3d(1, -1, -0x1.997c481a4b052p+4), Vector3d(0.75, 1, -0.0)};
  const ccd::CcdQuery query = make_query(PairKind::VertexFace, start, end);
  const ccd::exact::ContactTimeBounds exact = exact_contact_time_of(query);
  REQUIRE(exact.hit);
  REQUIRE(exact.lo > 0.6);
  REQUIRE(exact.hi < 0.62);
  const ccd::CcdResult result = ccd::continuous_collision(query);
  REQUIRE(result.hit);
  CHECK(result.state == ccd::CcdState::Hit);
  CHECK(result.toi <= exact.hi);
  CHECK(result.toi >= exact.lo - 1e-6);
}

TEST_CASE("primitives sharing a coordinate plane: decided on the plane, as the exact earliest contact",
          "[ccd][differential]") {
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 9401u : 9402u);
  int hits = 0, decided_on_plane = 0;
  for (int i = 0; i < 400; ++i) {
    const bool crossed = kind == PairKind::EdgeEdge && i % 4 == 3;
    const ccd::CcdQuery query = generator.pinned_query(kind, crossed);
    const ccd::exact::ContactTimeBounds exact = exact_contact_time_of(query);
    INFO("query " << i << " exact " << exact.hit << " in [" << exact.lo << ", " << exact.hi << "]");
    const std::optional<ccd::detail::PinnedAnswer> pinned = ccd::detail::pinned_segment_contact(query);
    if (pinned) {
      ++decided_on_plane;
      REQUIRE(pinned->hit == exact.hit);
      if (pinned->hit) {
        CHECK(pinned->toi <= exact.hi);
        CHECK(pinned->toi >= exact.lo - 1e-6);
      }
    }
    CHECK_FALSE((crossed && pinned));  // the points off the plane on both sides: not a segment test
    const ccd::CcdResult result = ccd::continuous_collision(query);
    REQUIRE(result.hit == exact.hit);
    if (result.hit) {
      CHECK(result.toi <= exact.hi);
      CHECK(result.toi >= exact.lo - 1e-6);
    }
    hits += exact.hit ? 1 : 0;
  }
  CHECK(hits > 60);
  CHECK(decided_on_plane > 200);
}

TEST_CASE("steps that start or end in an exact touch: hit and time of impact as the exact earliest contact's",
          "[ccd][differential]") {
  // A touch at an end is decided from that end's positions alone; one at the end counts only when nothing touches
  // before it, which the random other end makes happen both ways.
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  const bool at_start = GENERATE(false, true);
  QueryGenerator generator(kind == PairKind::VertexFace ? 9301u : 9302u);
  int hits = 0, earlier = 0;
  for (int i = 0; i < 300; ++i) {
    const ccd::CcdQuery query = generator.touching_end_query(kind, at_start);
    const ccd::exact::ContactTimeBounds exact = exact_contact_time_of(query);
    for (const ccd::CcdSettings& settings : {clothcd::test::exact_settings(), clothcd::test::approximate_settings()}) {
      const ccd::CcdResult result = ccd::continuous_collision(query, settings);
      INFO("query " << i << " exact decisions " << settings.decide_exactly << " toi " << result.toi << " exact in ["
                    << exact.lo << ", " << exact.hi << "]");
      REQUIRE((result.hit || !exact.hit));
      if (result.state == ccd::CcdState::ConservativeHit) continue;
      CHECK(result.hit == exact.hit);
      if (!result.hit) continue;
      CHECK(result.toi <= exact.hi);
      CHECK(result.toi >= exact.lo - 1e-6);
    }
    hits += exact.hit ? 1 : 0;
    earlier += exact.hit && exact.hi < 1.0 && exact.lo > 0.0 ? 1 : 0;
  }
  CHECK(hits > 200);
  INFO("hits " << hits << " before the end " << earlier);
  if (!at_start) CHECK(earlier > 5);  // contacts before the touch at the end
}

TEST_CASE("degenerate grid queries: fast CCD and filters never miss a reference collision", "[ccd][differential]") {
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 77u : 78u);
  Tally tally;
  for (int i = 0; i < 150; ++i) check_against_reference(generator.degenerate_query(kind), tally);
  CHECK(tally.reference_hits > tally.queries / 10);
}

TEST_CASE("queries scaled into the underflow range: fast CCD agrees with the reference", "[ccd][differential]") {
  // Coordinates from 2^-340 down to 2^-560 make the interval tier's products underflow (or start subnormal): its bounds
  // must still hold, and the exact tiers must take over where they cannot decide.
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  QueryGenerator generator(kind == PairKind::VertexFace ? 1701u : 1702u);
  Tally tally;
  for (int i = 0; i < 120; ++i) {
    const ccd::CcdQuery query = i % 2 ? generator.random_query(kind) : generator.degenerate_query(kind);
    check_against_reference(clothcd::test::scaled(query, std::ldexp(1.0, -(340 + 20 * (i % 12)))), tally);
  }
  CHECK(tally.reference_hits > tally.queries / 10);
}

TEST_CASE("the filters cull a useful share of random separated pairs", "[ccd][filters]") {
  // Not a safety property but a sanity check that the filters are switched on: far-apart pairs are culled.
  QueryGenerator generator(99u);
  int culled_nonpenetration = 0, culled_projection = 0, separated = 0;
  for (int i = 0; i < 400; ++i) {
    ccd::CcdQuery query = generator.random_query(PairKind::VertexFace);
    for (int j = 1; j < 4; ++j) {
      query.start[j].x() += 10.0;
      query.end[j].x() += 10.0;
    }
    if (ccd::exact_collision_reference(query)) continue;
    ++separated;
    culled_nonpenetration += ccd::nonpenetration_filter_culls(query) ? 1 : 0;
    culled_projection += ccd::projection_filter_culls(query) ? 1 : 0;
  }
  CHECK(culled_projection > separated * 9 / 10);
  CHECK(culled_nonpenetration > separated / 5);
}

TEST_CASE("thickness: every touching pair is still reported", "[ccd][thickness][differential]") {
  QueryGenerator generator(5u);
  ccd::CcdSettings settings;
  settings.thickness = 1e-3;
  for (int i = 0; i < 150; ++i) {
    const auto kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    const ccd::CcdQuery query = i % 3 ? generator.random_query(kind) : generator.degenerate_query(kind);
    if (!ccd::exact_collision_reference(query)) continue;
    CHECK(ccd::continuous_collision(query, settings).hit);
    CHECK_FALSE(ccd::projection_filter_culls(query, settings));
    CHECK_FALSE(ccd::combined_filters_cull(query, settings));
  }
}

TEST_CASE("batched filtering matches the single-query filters", "[ccd][filters]") {
  QueryGenerator generator(11u);
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 200; ++i)
    queries.push_back(generator.random_query(i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge));
  std::vector<std::uint8_t> keep;
  const std::size_t kept = ccd::filter_batch(queries, ccd::CcdFilter::Combined, {}, keep);
  REQUIRE(keep.size() == queries.size());
  std::size_t expected_kept = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    CHECK(keep[i] == (ccd::combined_filters_cull(queries[i]) ? 0 : 1));
    expected_kept += keep[i];
  }
  CHECK(kept == expected_kept);
  std::vector<ccd::CcdResult> results;
  ccd::continuous_collision_batch(queries, keep, clothcd::test::exact_settings(), results);
  for (std::size_t i = 0; i < queries.size(); ++i) CHECK(results[i].hit == ccd::exact_collision_reference(queries[i]));
}
