// The exact floating-point expansion tier of the thickness-0 CCD (src/ccd/expansion_collision.cpp) against the GMP
// reference, on seeded random and degenerate queries: whenever the tier answers, it must agree exactly, and on the
// degenerate families (coplanar for the whole step, touching at t = 0 or 1, integer grids, extreme magnitudes) it must
// answer most of the time, or it would not take load off the reference.
#include <gmpxx.h>

#include <cmath>
#include <random>

#include "ccd/ccd_test_support.hpp"
#include "ccd/expansion_collision.hpp"
#include "geometry/expansion.hpp"

using clothcd::PairKind;
using clothcd::test::make_query;
using clothcd::test::Vector3d;
namespace ccd = clothcd::ccd;
using clothcd::geometry::detail::Expansion;

namespace {

class Generator {
 public:
  explicit Generator(unsigned seed) : random_(seed) {}

  // Small integer coordinates (times `unit`), with the degenerate situations the benchmark's handcrafted queries are
  // made of: motion in one plane (D identically zero), points that do not move, a contact placed exactly at t = 0 or
  // t = 1 (vertex on the face or on an edge of it; edge through an endpoint or the middle of the other).
  ccd::CcdQuery grid_query(PairKind kind, double unit) {
    ccd::CcdQuery q;
    q.kind = kind;
    const int style = pick(4);
    for (int i = 0; i < 4; ++i) {
      q.start[i] = grid_vector(unit);
      q.end[i] = coin() ? q.start[i] : grid_vector(unit);
      if (style == 0) q.start[i].z() = q.end[i].z() = 0.0;  // coplanar for the whole step
    }
    if (style == 1 || style == 2) {
      auto& at = style == 1 ? q.start : q.end;  // touching exactly at t = 0 or t = 1
      const double w = 0.5 * pick(3);           // 0, 1/2 or 1: a corner, an edge middle or the far corner
      if (kind == PairKind::VertexFace) {
        at[0] = coin() ? Vector3d((1 - w) * at[1] + w * at[2]) : Vector3d((at[1] + at[2] + at[3]) * 0.25 + at[1] * 0.25);
      } else {
        at[0] = (1 - w) * at[2] + w * at[3];
      }
    }
    return q;
  }

  // Continuous coordinates around a contact at a random time, sometimes nudged by a rounding-sized amount.
  ccd::CcdQuery random_query(PairKind kind) {
    std::array<Vector3d, 4> contact;
    for (Vector3d& p : contact) p = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    const double u = uniform(0, 1), v = uniform(0, 1 - u);
    if (kind == PairKind::VertexFace) {
      contact[0] = (1 - u - v) * contact[1] + u * contact[2] + v * contact[3];
    } else {
      contact[1] = contact[0] + ((1 - u) * contact[2] + u * contact[3] - contact[0]) * uniform(0.5, 2.0);
    }
    const double t = uniform(0, 1);
    ccd::CcdQuery q;
    q.kind = kind;
    for (int i = 0; i < 4; ++i) {
      const Vector3d velocity{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      q.start[i] = contact[i] - t * velocity;
      q.end[i] = q.start[i] + velocity;
    }
    if (coin()) q.end[pick(4)][pick(3)] += coin() ? 1e-16 : -1e-16;
    return q;
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
  bool coin() { return std::bernoulli_distribution(0.5)(random_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  Vector3d grid_vector(double unit) {
    std::uniform_int_distribution<int> step(-3, 3);
    return Vector3d(step(random_), step(random_), step(random_)) * unit;
  }
  std::mt19937 random_;
};

struct Tally {
  int queries = 0, answered = 0, hits = 0;
};

void check_tier(const ccd::CcdQuery& q, Tally& tally) {
  const bool expected = ccd::exact_collision_reference(q);
  ++tally.queries;
  tally.hits += expected ? 1 : 0;
  INFO("start " << q.start[0].transpose() << " | " << q.start[1].transpose() << " | " << q.start[2].transpose()
                << " | " << q.start[3].transpose());
  INFO("end   " << q.end[0].transpose() << " | " << q.end[1].transpose() << " | " << q.end[2].transpose() << " | "
                << q.end[3].transpose());
  const auto answer = ccd::detail::expansion_collision(q);
  if (answer) {
    ++tally.answered;
    REQUIRE(answer->hit == expected);
    if (answer->hit) {
      CHECK(answer->toi >= 0.0);
      CHECK(answer->toi <= 1.0);
    }
  }
  const ccd::CcdResult exact = ccd::continuous_collision(q, clothcd::test::exact_settings());
  CHECK(exact.hit == expected);
  clothcd::test::check_conservative_answer(q, exact);
}

mpq_class exact_value(double x) {
  return mpq_class(x);
}

}  // namespace

TEST_CASE("expansion arithmetic is exact", "[ccd][expansion]") {
  std::mt19937 random(31);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  const auto draw = [&] { return std::ldexp(mantissa(random), exponent(random)); };
  for (int i = 0; i < 2000; ++i) {
    const double a = draw(), b = draw(), c = draw(), d = draw();
    const Expansion ea(a), eb(b), ec(c), ed(d);
    // (a + b)(c - d) - a c + a d - b c + b d is exactly zero.
    const Expansion zero = (ea + eb) * Expansion::difference(c, d) - ea * ec + ea * ed - eb * ec + eb * ed;
    CHECK(zero.is_zero());
    // The sign of a b c - d agrees with GMP, and so does the rounded estimate.
    const Expansion value = ea * eb * ec - ed;
    const mpq_class exact = exact_value(a) * exact_value(b) * exact_value(c) - exact_value(d);
    CHECK(value.sign() == sgn(exact));
    CHECK(value.estimate() == Approx(exact.get_d()).epsilon(1e-15));
    // In place, also with the operand itself: the same exact values.
    Expansion in_place = value;
    in_place += zero + ea * eb;
    CHECK((in_place - (value + ea * eb)).is_zero());
    in_place -= ea * eb;
    CHECK((in_place - value).is_zero());
    in_place += in_place;
    CHECK((in_place - value.scaled(2.0)).is_zero());
    in_place -= in_place;
    CHECK(in_place.is_zero());
  }
}

TEST_CASE("expansion compression keeps the value and never lengthens it", "[ccd][expansion]") {
  std::mt19937 random(32);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-200, 200);
  const auto draw = [&] { return std::ldexp(mantissa(random), exponent(random)); };
  for (int i = 0; i < 1000; ++i) {
    Expansion sum;
    for (int k = 0; k < 12; ++k) sum = sum + Expansion(draw()) * Expansion(draw());
    const Expansion compact = sum.compressed();
    CHECK((compact - sum).is_zero());
    CHECK(compact.sign() == sum.sign());
    CHECK(compact.estimate() == Approx(sum.estimate()).epsilon(1e-15));
  }
}

TEST_CASE("expansion tier decides coplanar motion through a point at a rational time", "[ccd][expansion]") {
  // Motion in the plane z = 0 (D identically zero) where one difference vector of W passes exactly through the
  // origin at t = k / q (not on the dyadic grid): its squared length is a quadratic with a double root there, which
  // bisection cannot bracket. Sometimes nudged by one unit in the last place, which splits the double root into two
  // roots about 1e-16 apart or none.
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  std::mt19937 random(kind == PairKind::VertexFace ? 4501u : 4502u);
  std::uniform_int_distribution<int> step(-3, 3), denominator(3, 7), coin(0, 3);
  const auto grid = [&] { return Vector3d(step(random), step(random), 0.0); };
  Tally tally;
  int answered_exact = 0, exact_queries = 0;
  for (int i = 0; i < 200; ++i) {
    const int q = denominator(random);
    const double s = static_cast<double>(std::uniform_int_distribution<int>(1, q - 1)(random)) / q;
    const Vector3d from = grid(), to = grid();
    ccd::CcdQuery query;
    query.kind = kind;
    for (int j = 0; j < 4; ++j) {
      query.start[j] = grid();
      query.end[j] = coin(random) == 0 ? query.start[j] : grid();
    }
    // Point 0 moves from `from` to `to`; the static point 2 (a face vertex, or an endpoint of the other edge) lies on
    // its path at the parameter s (rounded: the exact contact time is the rational that rounding gives).
    query.start[0] = from;
    query.end[0] = to;
    query.start[2] = query.end[2] = from + s * (to - from);
    const bool nudge = coin(random) == 0;
    if (nudge) query.end[2].x() = std::nextafter(query.end[2].x(), 10.0);
    check_tier(query, tally);
    if (!nudge) {
      ++exact_queries;
      answered_exact += ccd::detail::expansion_collision(query) ? 1 : 0;
    }
  }
  CHECK(tally.hits > tally.queries / 10);
  CHECK(answered_exact > exact_queries * 9 / 10);
  CHECK(tally.answered > tally.queries * 3 / 4);
}

TEST_CASE("expansion tier agrees with the reference on degenerate grid queries", "[ccd][expansion][differential]") {
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  // Exactly representable units: plain, tiny, huge (beyond the interval path's range) and with a ragged mantissa.
  const double unit = GENERATE(0.5, 0x1p-600, 0x1p+300, 0.1);
  Generator generator(kind == PairKind::VertexFace ? 1201u : 1202u);
  Tally tally;
  for (int i = 0; i < 250; ++i) check_tier(generator.grid_query(kind, unit), tally);
  CHECK(tally.hits > tally.queries / 10);
  // Adversarial grids: shared roots of two quadratic sign polynomials and double roots of D stay with the reference.
  CHECK(tally.answered > tally.queries * 3 / 4);
}

TEST_CASE("expansion tier decides grid queries perturbed far below rounding", "[ccd][expansion][differential]") {
  // The handcrafted benchmark's hardest queries: a touching or coplanar grid configuration moved by amounts near
  // 2^-100 (rotation noise), so sign polynomials nearly vanish at an irrational root of D and values span hundreds of
  // binary orders of magnitude (long expansions, pseudo-division of D by a sign polynomial).
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  Generator generator(kind == PairKind::VertexFace ? 9301u : 9302u);
  std::mt19937 random(kind == PairKind::VertexFace ? 9303u : 9304u);
  std::uniform_int_distribution<int> noise(-7, 7), pick(0, 3), axis(0, 2);
  Tally tally;
  for (int i = 0; i < 200; ++i) {
    ccd::CcdQuery q = generator.grid_query(kind, 0.5);
    for (int k = 0; k < 3; ++k) {
      auto& points = noise(random) > 0 ? q.start : q.end;
      points[pick(random)][axis(random)] += std::ldexp(noise(random), -100 - 3 * k);
    }
    check_tier(q, tally);
  }
  CHECK(tally.hits > tally.queries / 10);
  CHECK(tally.answered > tally.queries * 9 / 10);
}

TEST_CASE("expansion tier agrees with the reference on random queries", "[ccd][expansion][differential]") {
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  Generator generator(kind == PairKind::VertexFace ? 77001u : 77002u);
  Tally tally;
  for (int i = 0; i < 250; ++i) check_tier(generator.random_query(kind), tally);
  CHECK(tally.hits > tally.queries / 5);
  CHECK(tally.answered > tally.queries * 9 / 10);
}

TEST_CASE("expansion tier decides exact touching and whole-step coplanar motion", "[ccd][expansion]") {
  using V = Vector3d;
  const V a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // The vertex comes down onto the middle of the edge ab exactly at t = 1.
  const auto edge_touch = make_query(PairKind::VertexFace, {V(1, 0, 1), a, b, c}, {V(1, 0, 0), a, b, c});
  // The vertex slides in the triangle's plane along the line of edge ab, onto it at t = 1/2 and beyond it.
  const auto sliding = make_query(PairKind::VertexFace, {V(-2, 0, 0), a, b, c}, {V(-1, 0, 0), a, b, c});
  const auto sliding_in = make_query(PairKind::VertexFace, {V(-2, 0, 0), a, b, c}, {V(2, 0, 0), a, b, c});
  // Coplanar parallel edges that never meet, and two that overlap along a line at t = 1/2.
  const auto parallel_miss =
      make_query(PairKind::EdgeEdge, {V(0, 1, 0), V(1, 1, 0), V(0, 0, 0), V(1, 0, 0)},
                 {V(0, 0.5, 0), V(1, 0.5, 0), V(0, 0, 0), V(1, 0, 0)});
  const auto parallel_hit = make_query(PairKind::EdgeEdge, {V(0, 1, 0), V(1, 1, 0), V(0, 0, 0), V(1, 0, 0)},
                                       {V(0.5, -1, 0), V(1.5, -1, 0), V(0, 0, 0), V(1, 0, 0)});
  for (const auto& [query, expected] :
       {std::pair{edge_touch, true}, {sliding, false}, {sliding_in, true}, {parallel_miss, false},
        {parallel_hit, true}}) {
    REQUIRE(ccd::exact_collision_reference(query) == expected);
    const auto answer = ccd::detail::expansion_collision(query);
    REQUIRE(answer.has_value());
    CHECK(answer->hit == expected);
    const ccd::CcdResult result = ccd::continuous_collision(query, clothcd::test::exact_settings());
    CHECK(result.hit == expected);
    CHECK_FALSE(result.exact_fallback);
    clothcd::test::check_conservative_answer(query, result);
  }
}

TEST_CASE("expansion tier decides touching at a time where points align on an axis", "[ccd][expansion][differential]") {
  // The handcrafted queries' sliding contacts: a face that stays parallel to the plane y = 0 (static, so D is linear,
  // or moving with one common y velocity and deforming in x and z, so D is a cubic with the factor v_y - f_y) and a
  // vertex whose x and z stay on the middle of an edge, on a corner, or a grid step inside or outside the face. The
  // contact time, where the vertex's y meets the face's, is a rational like 1/3 off the dyadic grid.
  std::mt19937 random(6601u);
  std::uniform_int_distribution<int> step(-3, 3), where(0, 3), speed(1, 4);
  const auto grid = [&] { return Vector3d(2 * step(random), 0.0, 2 * step(random)); };
  Tally tally;
  for (int i = 0; i < 300; ++i) {
    const bool static_face = i % 2 == 0;
    ccd::CcdQuery q;
    q.kind = PairKind::VertexFace;
    const double face_y0 = step(random), face_vy = static_face ? 0.0 : step(random);
    for (int j = 1; j < 4; ++j) {
      q.start[j] = grid();
      q.end[j] = static_face ? q.start[j] : grid();
      q.start[j].y() = face_y0;
      q.end[j].y() = face_y0 + face_vy;
    }
    // The vertex's x and z, at every time: on edge 1-2's middle, on corner 1, one step beside corner 1, or the
    // centroid-ish point (1 + 1 + 2 + 3) / 4 of the face.
    const int spot = where(random);
    const auto in_plane = [&](const std::array<Vector3d, 4>& p) -> Vector3d {
      if (spot == 0) return 0.5 * (p[1] + p[2]);
      if (spot == 1) return p[1];
      if (spot == 2) return p[1] + Vector3d(1.0, 0.0, 0.0);
      return 0.25 * (2.0 * p[1] + p[2] + p[3]);
    };
    q.start[0] = in_plane(q.start);
    q.end[0] = in_plane(q.end);
    // y crosses the face's plane at t = 1 / (k + 1): start 1 above it, closing in at k + 1 units per step.
    const int k = speed(random);
    q.start[0].y() = face_y0 + 1.0;
    q.end[0].y() = face_y0 + face_vy + 1.0 - (k + 1);
    check_tier(q, tally);
  }
  CHECK(tally.hits > tally.queries / 4);
  CHECK(tally.answered > tally.queries * 95 / 100);
}

TEST_CASE("expansion tier decides coplanar motion in a turning plane", "[ccd][expansion][differential]") {
  // D identically zero without an axis-aligned plane: one point (the vertex, or the first edge's second endpoint) is a
  // fixed affine combination of the other three, which move freely on a grid, so the four stay coplanar while their
  // plane turns; the plane's normal may keep one strict sign on an axis for the whole step (that projection alone
  // decides) or not (every projection), and the triangle may degenerate in between.
  const auto kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  std::mt19937 random(kind == PairKind::VertexFace ? 7101u : 7102u);
  std::uniform_int_distribution<int> step(-3, 3), weight(-2, 6), coin(0, 3);
  const auto grid = [&] { return Vector3d(step(random), step(random), step(random)); };
  const int combined = kind == PairKind::VertexFace ? 0 : 1;
  Tally tally;
  for (int i = 0; i < 300; ++i) {
    ccd::CcdQuery q;
    q.kind = kind;
    for (int j = 0; j < 4; ++j) {
      q.start[j] = grid();
      q.end[j] = coin(random) == 0 ? q.start[j] : grid();
    }
    const double a = 0.25 * weight(random), b = 0.25 * weight(random);  // exact dyadic weights, sum of three is 1
    std::array<int, 3> others{};
    for (int j = 0, n = 0; j < 4; ++j)
      if (j != combined) others[static_cast<std::size_t>(n++)] = j;
    for (auto* points : {&q.start, &q.end}) {
      auto& p = *points;
      p[combined] = (1 - a - b) * p[others[0]] + a * p[others[1]] + b * p[others[2]];
    }
    check_tier(q, tally);
  }
  CHECK(tally.hits > tally.queries / 10);
  CHECK(tally.answered > tally.queries * 9 / 10);
}
