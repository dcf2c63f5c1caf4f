// Thickness (minimum separation h > 0) CCD against a slow brute-force reference: the distance of the two primitives
// sampled on a fine grid of their parameters at many times. A grid distance <= h proves the pair comes within h, so
// the CCD must report it (zero false negatives); far-apart coplanar (flat cloth) pairs must be decided Separated.
#include <algorithm>
#include <limits>
#include <random>

#include "ccd/ccd_test_support.hpp"
#include "ccd/sampled_distance.hpp"
#include "geometry/pair_distance.hpp"

using clothcd::PairKind;
using clothcd::test::make_query;
using clothcd::test::Vector3d;
namespace ccd = clothcd::ccd;

namespace {

constexpr int kGrid = 24;
constexpr int kTimes = 96;

double grid_distance(const ccd::CcdQuery& query, double t) {
  return clothcd::test::sampled_distance(query, t, kGrid);
}

double reference_min_distance(const ccd::CcdQuery& query) {
  return clothcd::test::sampled_min_distance(query, kGrid, kTimes);
}

class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  Vector3d vector(double size) { return {uniform(-size, size), uniform(-size, size), uniform(-size, size)}; }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine_); }

 private:
  std::mt19937 engine_;
};

// Random pair of a kind, optionally degenerate: zero-length edge / zero-area triangle, parallel edges, coplanar.
ccd::CcdQuery random_pair(Random& random, PairKind kind, int variant) {
  std::array<Vector3d, 4> start, end;
  for (int i = 0; i < 4; ++i) {
    start[i] = random.vector(0.1);
    end[i] = start[i] + random.vector(0.05);
  }
  switch (variant) {
    case 1:  // zero-length edge a / vertex collapses onto t0
      start[1] = start[kind == PairKind::VertexFace ? 2 : 0];
      end[1] = end[kind == PairKind::VertexFace ? 2 : 0];
      break;
    case 2: {  // zero-area triangle (collinear corners) / parallel edges
      const int from = kind == PairKind::VertexFace ? 1 : 0;
      const int to = kind == PairKind::VertexFace ? 2 : 1;
      start[3] = start[2] + 0.5 * (start[to] - start[from]);
      end[3] = end[2] + 0.5 * (end[to] - end[from]);
      break;
    }
    case 3:  // everything in the plane z = 0 at both ends (flat cloth)
      for (int i = 0; i < 4; ++i) start[i].z() = end[i].z() = 0.0;
      break;
    default:
      break;
  }
  return make_query(kind, start, end);
}

}  // namespace

TEST_CASE("thickness: a flat coplanar pair 8 cm apart is separated, not conservative", "[ccd][thickness]") {
  ccd::CcdSettings settings;
  settings.thickness = 0.004;
  const Vector3d down(0, 0, -0.001);
  const std::array<Vector3d, 4> vf{Vector3d(0.08, 0, 0), Vector3d(0, 0, 0), Vector3d(-0.01, 0.01, 0),
                                   Vector3d(-0.01, -0.01, 0)};
  const std::array<Vector3d, 4> ee{Vector3d(0.08, 0, 0), Vector3d(0.09, 0.01, 0), Vector3d(0, 0, 0),
                                   Vector3d(-0.01, 0.01, 0)};
  for (const auto& [kind, start] : {std::pair{PairKind::VertexFace, vf}, std::pair{PairKind::EdgeEdge, ee}}) {
    std::array<Vector3d, 4> end = start;
    for (Vector3d& p : end) p += down;
    const ccd::CcdResult result = ccd::continuous_collision(make_query(kind, start, end), settings);
    CHECK(result.state == ccd::CcdState::Separated);
    CHECK_FALSE(result.hit);
    CHECK_FALSE(result.exact_fallback);
  }
}

TEST_CASE("thickness: no false reports on random far-apart coplanar pairs", "[ccd][thickness]") {
  Random random(21u);
  ccd::CcdSettings settings;
  settings.thickness = 0.004;
  int far = 0, reported = 0;
  for (int i = 0; i < 300; ++i) {
    const PairKind kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    ccd::CcdQuery query = random_pair(random, kind, 3);
    const Vector3d drop(0, 0, random.uniform(-0.002, 0.002));
    for (Vector3d& p : query.end) p = p + drop;
    const double distance = reference_min_distance(query);
    if (distance <= settings.thickness) {
      CHECK(ccd::continuous_collision(query, settings).hit);
      continue;
    }
    // The grid is an upper bound, so demand a clear gap before calling a report false.
    if (distance < 2 * settings.thickness) continue;
    ++far;
    reported += ccd::continuous_collision(query, settings).hit ? 1 : 0;
  }
  CHECK(far > 100);
  CHECK(reported == 0);
}

TEST_CASE("thickness: zero false negatives against the brute-force reference", "[ccd][thickness][differential]") {
  Random random(7u);
  int hits = 0;
  for (int i = 0; i < 240; ++i) {
    const PairKind kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    const ccd::CcdQuery query = random_pair(random, kind, (i / 2) % 4);
    const double distance = reference_min_distance(query);
    ccd::CcdSettings settings;
    // Contact exactly at h (the sampled minimum), or a random h around the minimum.
    settings.thickness = i % 3 == 0 ? distance : random.uniform(0.001, 0.05);
    if (!(settings.thickness > 0)) continue;
    const ccd::CcdResult result = ccd::continuous_collision(query, settings);
    if (distance <= settings.thickness) {
      INFO("query " << i << " distance " << distance << " thickness " << settings.thickness);
      CHECK(result.hit);
      CHECK_FALSE(ccd::projection_filter_culls(query, settings));
      CHECK_FALSE(ccd::combined_filters_cull(query, settings));
      ++hits;
    }
    if (result.hit) {
      // toi is a lower bound of the first contact: before it the distance (of which the grid gives an upper bound)
      // stays above h.
      for (int k = 0; k * 1.0 / kTimes < result.toi; ++k)
        CHECK(grid_distance(query, k * 1.0 / kTimes) > settings.thickness * (1 - 1e-9));
    }
  }
  CHECK(hits > 60);
}

TEST_CASE("thickness: hits carry the closest-point parameters and normal", "[ccd][thickness]") {
  ccd::CcdSettings settings;
  settings.thickness = 0.01;
  const std::array<Vector3d, 4> tri{Vector3d(0.2, 0.3, 1), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  std::array<Vector3d, 4> tri_end = tri;
  tri_end[0] = Vector3d(0.2, 0.3, -1);
  const ccd::CcdResult vf = ccd::continuous_collision(make_query(PairKind::VertexFace, tri, tri_end), settings);
  REQUIRE(vf.state == ccd::CcdState::Hit);
  CHECK(vf.toi == Approx(0.495).margin(1e-6));  // distance 1 - 2t reaches 0.01 at t = 0.495
  CHECK(vf.toi <= 0.495);
  CHECK(vf.parameters[0] == Approx(0.2).margin(1e-9));
  CHECK(vf.parameters[1] == Approx(0.3).margin(1e-9));
  CHECK((vf.normal - Vector3d(0, 0, 1)).norm() < 1e-9);

  // Edge a along y at x = 0.5, z descending; edge b along x.
  const std::array<Vector3d, 4> edges{Vector3d(0.5, -1, 1), Vector3d(0.5, 1, 1), Vector3d(0, 0, 0), Vector3d(1, 0, 0)};
  std::array<Vector3d, 4> edges_end = edges;
  edges_end[0].z() = edges_end[1].z() = 0.5;
  const ccd::CcdResult far = ccd::continuous_collision(make_query(PairKind::EdgeEdge, edges, edges_end), settings);
  CHECK(far.state == ccd::CcdState::Separated);
  edges_end[0].z() = edges_end[1].z() = -1;
  const ccd::CcdResult ee = ccd::continuous_collision(make_query(PairKind::EdgeEdge, edges, edges_end), settings);
  REQUIRE(ee.state == ccd::CcdState::Hit);
  CHECK(ee.toi <= 0.495);
  CHECK(ee.toi == Approx(0.495).margin(1e-6));
  CHECK(ee.parameters[0] == Approx(0.5).margin(1e-9));
  CHECK(ee.parameters[1] == Approx(0.5).margin(1e-9));
  CHECK((ee.normal - Vector3d(0, 0, 1)).norm() < 1e-9);
}

namespace {

// Pairs within h and pairs reported separated, over the queries given to check_against_reference.
struct ReferenceTally {
  int within = 0;
  int separated = 0;
};

// The thickness CCD on `query` against the brute-force distance: a pair that comes within h must be reported, and a
// hit's time of impact must be a lower bound (every grid time before it is farther than h).
void check_against_reference(const ccd::CcdQuery& query, const ccd::CcdSettings& settings, ReferenceTally& tally) {
  const double h = settings.thickness;
  const double distance = reference_min_distance(query);
  const ccd::CcdResult result = ccd::continuous_collision(query, settings);
  INFO("distance / h " << distance / h);
  if (distance <= h) {
    CHECK(result.hit);
    ++tally.within;
  }
  tally.separated += result.hit ? 0 : 1;
  if (result.hit) {
    for (int k = 0; k * 1.0 / kTimes < result.toi; ++k) CHECK(grid_distance(query, k * 1.0 / kTimes) > h * (1 - 1e-9));
  }
}

// Checks 400 pairs, vertex-face and edge-edge in turn, that make(kind, random, start, end) builds, against the
// reference at thickness h.
template <class Make>
ReferenceTally check_generated_pairs(unsigned seed, double h, const Make& make) {
  Random random(seed);
  ccd::CcdSettings settings;
  settings.thickness = h;
  ReferenceTally tally;
  for (int i = 0; i < 400; ++i) {
    const PairKind kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    std::array<Vector3d, 4> start, end;
    make(kind, random, start, end);
    INFO("pair " << i);
    check_against_reference(make_query(kind, start, end), settings, tally);
  }
  return tally;
}

}  // namespace

TEST_CASE("thickness: pairs sliding past at about h are never missed", "[ccd][thickness][differential]") {
  // A vertex over a face, or an edge over an edge, moving far sideways while the gap changes little: the Lipschitz
  // bound cannot clear such a step, so the search relies on projections onto the gap direction, which must not drop
  // a pair that comes within h.
  const double h = 0.004;
  const ReferenceTally tally = check_generated_pairs(
      31u, h, [h](PairKind kind, Random& random, std::array<Vector3d, 4>& start, std::array<Vector3d, 4>& end) {
        if (kind == PairKind::VertexFace) {
          start = {Vector3d(0, 0, 0), Vector3d(-0.05, -0.05, 0), Vector3d(0.05, -0.05, 0), Vector3d(0, 0.05, 0)};
        } else {
          start = {Vector3d(-0.03, 0, 0), Vector3d(0.03, 0, 0), Vector3d(0, -0.03, 0), Vector3d(0, 0.03, 0)};
        }
        const double gap0 = random.uniform(0.5 * h, 1.6 * h), gap1 = random.uniform(0.5 * h, 1.6 * h);
        const Vector3d slide(random.uniform(-0.04, 0.04), random.uniform(-0.04, 0.04), 0.0);
        const Vector3d tilt = random.vector(0.002);
        end = start;
        const int first_count = kind == PairKind::VertexFace ? 1 : 2;
        for (int k = 0; k < first_count; ++k) {
          start[k].z() += gap0;
          end[k].z() += gap1;
          end[k] += slide + (k == 0 ? tilt : Vector3d(-tilt));
        }
      });
  CHECK(tally.within > 50);
  CHECK(tally.separated > 50);
}

TEST_CASE("thickness: a pair far apart at the start is cleared from it only when it cannot come within h",
          "[ccd][thickness]") {
  // A vertex 5 cm above a triangle moving towards it (straight down or slanted) or sideways by `move`: d(0) - L is
  // above h for the short moves only; the answer must follow the brute-force distance either way.
  const double h = 0.004, height = 0.05;
  ccd::CcdSettings settings;
  settings.thickness = h;
  const std::array<Vector3d, 4> start{Vector3d(0, 0, height), Vector3d(-0.1, -0.1, 0), Vector3d(0.1, -0.1, 0),
                                      Vector3d(0, 0.1, 0)};
  int hits = 0, separated = 0;
  for (const double move : {height - h - 1e-3, height - h - 1e-6, height - h + 1e-6, height - h + 1e-3, 0.2}) {
    for (const Vector3d& direction : {Vector3d(0, 0, -1), Vector3d(0.6, 0, -0.8), Vector3d(1, 0, 0)}) {
      std::array<Vector3d, 4> end = start;
      end[0] += move * direction;
      const ccd::CcdQuery query = make_query(PairKind::VertexFace, start, end);
      const ccd::CcdResult result = ccd::continuous_collision(query, settings);
      const double distance = clothcd::test::sampled_min_distance(query, 16, 2048);
      INFO("move " << move << " direction " << direction.transpose() << " distance " << distance);
      if (distance <= h) CHECK(result.hit);
      if (distance > h + 1e-5) CHECK(result.state == ccd::CcdState::Separated);
      hits += result.hit ? 1 : 0;
      separated += result.hit ? 0 : 1;
    }
  }
  CHECK(hits >= 4);
  CHECK(separated >= 6);
}

TEST_CASE("thickness: pairs side by side about h apart are never missed", "[ccd][thickness][differential]") {
  // A cloth resting flat: a vertex beside a triangle edge, or an edge beside another, in (nearly) one plane at a
  // sideways gap of 0.3 h to 2 h, tilted a little and moving a little (most of the pairs a resting cloth sends to the
  // search are side by side like this). Every pair the brute-force distance puts within h must be reported.
  const double h = 0.004;
  const ReferenceTally tally = check_generated_pairs(
      11u, h, [h](PairKind kind, Random& random, std::array<Vector3d, 4>& start, std::array<Vector3d, 4>& end) {
        const Vector3d u = random.vector(1.0).normalized();
        const Vector3d v = u.unitOrthogonal();
        const Vector3d w = u.cross(v);  // the plane's normal
        const Vector3d origin = random.vector(1.0);
        const double gap = h * random.uniform(0.3, 2.0), size = 0.02;
        if (kind == PairKind::VertexFace) {
          // Triangle edge along u through the origin, the triangle on the -v side, the vertex on the +v side.
          start = {origin + random.uniform(-0.5, 0.5) * size * u + gap * v + random.uniform(-0.5, 0.5) * gap * w,
                   origin - 0.5 * size * u, origin + 0.5 * size * u,
                   origin - size * v + random.uniform(-0.2, 0.2) * size * w};
        } else {
          const Vector3d tilt = random.uniform(-0.3, 0.3) * u + random.uniform(-0.3, 0.3) * w;
          start = {origin + gap * v - 0.5 * size * u, origin + gap * v + 0.5 * size * (u + tilt),
                   origin - 0.5 * size * u, origin + 0.5 * size * u};
          start[0] += random.uniform(0.0, 1.0) * size * v;  // sometimes splayed apart
        }
        end = start;
        for (Vector3d& p : end) p += random.vector(0.2 * h);
      });
  CHECK(tally.within > 40);
  CHECK(tally.separated > 100);
}

TEST_CASE("thickness: a reported pair comes within the thickness plus the documented margin",
          "[ccd][thickness][differential]") {
  // The margin of the thickness test is about 1e-7 of the pair's extent (ccd::CcdSettings::thickness). The reference
  // minimum distance: the closest points of the two primitives at 20,001 evenly spaced times, an upper bound of the
  // true minimum by at most half a time step times the largest relative speed of two points.
  Random random(11u);
  int hits = 0, near_misses = 0;
  for (int i = 0; i < 200; ++i) {
    const PairKind kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    const ccd::CcdQuery query = random_pair(random, kind, (i / 2) % 4);
    const double sampled = reference_min_distance(query);
    ccd::CcdSettings settings;
    // Thicknesses just below the pair's minimum distance: the pairs that must not be reported beyond the margin.
    settings.thickness = sampled * (i % 3 == 0 ? 0.999 : 0.9);
    if (!(settings.thickness > 0)) continue;
    if (!ccd::continuous_collision(query, settings).hit) {
      ++near_misses;
      continue;
    }
    ++hits;
    constexpr int kSteps = 20000;
    double extent = 0.0, speed = 0.0, closest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        extent = std::max({extent, (query.start[a] - query.start[b]).norm(), (query.end[a] - query.end[b]).norm()});
        speed = std::max(speed, ((query.end[a] - query.start[a]) - (query.end[b] - query.start[b])).norm());
      }
    }
    for (int k = 0; k <= kSteps; ++k) {
      const double t = static_cast<double>(k) / kSteps;
      std::array<Vector3d, 4> x;
      for (int p = 0; p < 4; ++p) x[p] = (1 - t) * query.start[p] + t * query.end[p];
      const double d = kind == PairKind::VertexFace
                           ? clothcd::geometry::point_triangle_closest(x[0], x[1], x[2], x[3]).distance
                           : clothcd::geometry::segment_segment_closest(x[0], x[1], x[2], x[3]).distance;
      closest = std::min(closest, d);
    }
    INFO("query " << i << " thickness " << settings.thickness << " closest " << closest);
    CHECK(closest - 0.5 * speed / kSteps <= settings.thickness + 2e-7 * extent);
  }
  CHECK(near_misses > 50);
  CHECK(hits > 5);  // pairs whose true minimum lies below the 0.999 of the sampled one
}
