// The thickness-0 fast tier's error bounds: every rounded value it decides on (W at a time, the projected cross
// products' Bernstein coefficients on a piece, D's coefficients on the step and on halved pieces) lies within its
// stated bound of the exact rational value, on random queries from huge to tiny magnitudes, with coordinate
// differences far below the coordinates, and on degenerate ones.
#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "ccd/rounded_search.hpp"
#include "ccd_test_support.hpp"

using clothcd::PairKind;
using clothcd::ccd::CcdQuery;
using clothcd::ccd::detail::RoundedCubic;
using clothcd::ccd::detail::RoundedQuery;
using clothcd::ccd::detail::WPoints;
using Eigen::Vector3d;

namespace {

using ExactPoints = std::array<std::array<mpq_class, 4>, 3>;  // [axis][point], as WPoints

// A random query: a base point of random magnitude (2^-1060, subnormal, to 2^90), the eight positions near it at
// offsets of another random magnitude, some of them far smaller again (features far below the primitives' size), some
// coordinates shared (degenerate: equal points, coordinate planes), now and then a point equal to another.
CcdQuery random_query(std::mt19937& random) {
  std::uniform_int_distribution<int> base_exponent(-1060, 90), spread_exponent(-50, 2), smaller(0, 60), pick(0, 7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double base = std::ldexp(1.0, base_exponent(random));
  const double spread = base * std::ldexp(1.0, spread_exponent(random));
  const Vector3d centre(base * unit(random), base * unit(random), base * unit(random));
  CcdQuery query;
  query.kind = pick(random) < 4 ? PairKind::VertexFace : PairKind::EdgeEdge;
  for (int i = 0; i < 8; ++i) {
    Vector3d& x = i < 4 ? query.start[i] : query.end[i - 4];
    for (int d = 0; d < 3; ++d) {
      const int choice = pick(random);
      const double offset = spread * unit(random) * (choice == 1 ? std::ldexp(1.0, -smaller(random)) : 1.0);
      x[d] = choice == 0 ? centre[d] : centre[d] + offset;
    }
    if (i % 4 > 0 && pick(random) == 0) x = i < 4 ? query.start[i - 1] : query.end[i - 5];  // a repeated point
  }
  return query;
}

mpq_class exact(double x) {
  return mpq_class(x);
}

// W at the step's start (end = 0) or end (end = 1), exactly.
ExactPoints exact_w(const CcdQuery& query, int end) {
  const std::array<Vector3d, 4>& x = end == 0 ? query.start : query.end;
  static constexpr int vertex_face[4][2] = {{0, 1}, {0, 2}, {0, 3}, {0, 1}};
  static constexpr int edge_edge[4][2] = {{0, 2}, {0, 3}, {1, 2}, {1, 3}};
  const auto& pairs = query.kind == PairKind::VertexFace ? vertex_face : edge_edge;
  ExactPoints w;
  for (int d = 0; d < 3; ++d)
    for (int m = 0; m < 4; ++m) w[d][m] = exact(x[pairs[m][0]][d]) - exact(x[pairs[m][1]][d]);
  return w;
}

ExactPoints exact_w_at(const CcdQuery& query, const mpq_class& t) {
  const ExactPoints w0 = exact_w(query, 0), w1 = exact_w(query, 1);
  ExactPoints w;
  for (int d = 0; d < 3; ++d)
    for (int m = 0; m < 4; ++m) w[d][m] = (1 - t) * w0[d][m] + t * w1[d][m];
  return w;
}

bool within(double rounded, const mpq_class& value, double error) {
  return abs(exact(rounded) - value) <= exact(error);
}

// D's tripled Bernstein coefficients on the step, exactly (the determinants of the edge vectors from x0).
std::array<mpq_class, 4> exact_d(const CcdQuery& query) {
  using Vec = std::array<mpq_class, 3>;
  const auto edge = [&](const std::array<Vector3d, 4>& x, int i) {
    return Vec{exact(x[i][0]) - exact(x[0][0]), exact(x[i][1]) - exact(x[0][1]), exact(x[i][2]) - exact(x[0][2])};
  };
  const auto det = [](const Vec& a, const Vec& b, const Vec& c) -> mpq_class {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  };
  const Vec a0 = edge(query.start, 1), b0 = edge(query.start, 2), c0 = edge(query.start, 3);
  const Vec a1 = edge(query.end, 1), b1 = edge(query.end, 2), c1 = edge(query.end, 3);
  return {3 * det(a0, b0, c0), det(a1, b0, c0) + det(a0, b1, c0) + det(a0, b0, c1),
          det(a1, b1, c0) + det(a1, b0, c1) + det(a0, b1, c1), 3 * det(a1, b1, c1)};
}

// A random query, its rounded form, and a random dyadic piece [t0, t1] of its step, at most max_depth halvings deep.
struct RandomPiece {
  CcdQuery query;
  RoundedQuery rounded;
  double t0 = 0.0;
  double t1 = 1.0;
};

RandomPiece random_piece(std::mt19937& random, int max_depth) {
  RandomPiece piece;
  piece.query = random_query(random);
  const std::optional<RoundedQuery> rounded = clothcd::ccd::detail::rounded_query(piece.query);
  REQUIRE(rounded);
  piece.rounded = *rounded;
  const int levels = std::uniform_int_distribution<int>(0, max_depth)(random);
  const long k = std::uniform_int_distribution<long>(0, (1L << levels) - 1)(random);
  piece.t0 = std::ldexp(static_cast<double>(k), -levels);
  piece.t1 = std::ldexp(static_cast<double>(k + 1), -levels);
  return piece;
}

}  // namespace

TEST_CASE("rounded W at dyadic times is within point_error of the exact W", "[ccd][rounded]") {
  std::mt19937 random(20261129u);
  int inexact = 0;
  for (int i = 0; i < 3000; ++i) {
    const RandomPiece piece = random_piece(random, 30);
    const RoundedQuery& rounded = piece.rounded;
    for (const double t : {piece.t0, piece.t1}) {
      WPoints w;
      clothcd::ccd::detail::point_at(rounded, t, w);
      const ExactPoints truth = exact_w_at(piece.query, exact(t));
      for (int d = 0; d < 3; ++d) {
        for (int m = 0; m < 4; ++m) {
          INFO("query " << i << " t " << t << " axis " << d << " point " << m);
          CHECK(within(w[d][m], truth[d][m], rounded.point_error[d][m]));
          CHECK(abs(truth[d][m]) <= exact(rounded.magnitude[d][m]));
          CHECK(std::abs(w[d][m]) <= rounded.magnitude[d][m]);
          inexact += exact(w[d][m]) != truth[d][m] ? 1 : 0;
        }
      }
    }
  }
  CHECK(inexact > 5000);  // rounding errors occur, or the test proves little
}

TEST_CASE("rounded cross products' Bernstein coefficients on a piece are within cross_error", "[ccd][rounded]") {
  std::mt19937 random(11u);
  std::uniform_int_distribution<int> axis(0, 2), point(0, 3);
  int inexact = 0;
  for (int i = 0; i < 3000; ++i) {
    const RandomPiece piece = random_piece(random, 20);
    const double t0 = piece.t0, t1 = piece.t1;
    WPoints p, q;
    clothcd::ccd::detail::point_at(piece.rounded, t0, p);
    clothcd::ccd::detail::point_at(piece.rounded, t1, q);
    const ExactPoints ep = exact_w_at(piece.query, exact(t0)), eq = exact_w_at(piece.query, exact(t1));
    const int k_axis = axis(random), a = point(random), b = point(random);
    const int u = (k_axis + 1) % 3, v = (k_axis + 2) % 3;
    const std::array<mpq_class, 3> truth = {
        ep[u][a] * ep[v][b] - ep[v][a] * ep[u][b],
        (ep[u][a] * eq[v][b] + eq[u][a] * ep[v][b] - ep[v][a] * eq[u][b] - eq[v][a] * ep[u][b]) / 2,
        eq[u][a] * eq[v][b] - eq[v][a] * eq[u][b]};
    const std::array<double, 3> c = clothcd::ccd::detail::cross_coefficients(p, q, a, b, k_axis);
    for (int j = 0; j < 3; ++j) {
      INFO("query " << i << " piece [" << t0 << ", " << t1 << "] coefficient " << j);
      CHECK(within(c[j], truth[j], clothcd::ccd::detail::cross_error(piece.rounded, a, b, k_axis)));
      inexact += exact(c[j]) != truth[j] ? 1 : 0;
    }
  }
  CHECK(inexact > 3000);
}

namespace {

// Halves `cubic` `levels` times along a random path and checks every piece's coefficients against the exact halving
// of `truth`; returns how many were inexact.
int check_halving_path(std::mt19937& random, RoundedCubic cubic, std::array<mpq_class, 4> truth, int levels,
                       double halving_error) {
  std::uniform_int_distribution<int> side(0, 1);
  int inexact = 0;
  for (int level = 0;; ++level) {
    for (int j = 0; j < 4; ++j) {
      INFO("level " << level << " coefficient " << j);
      CHECK(within(cubic.b[j], truth[j], cubic.error));
      inexact += exact(cubic.b[j]) != truth[j] ? 1 : 0;
    }
    if (level == levels) return inexact;
    RoundedCubic left, right;
    clothcd::ccd::detail::halve(cubic, halving_error, left, right);
    const mpq_class b01 = (truth[0] + truth[1]) / 2, b12 = (truth[1] + truth[2]) / 2, b23 = (truth[2] + truth[3]) / 2;
    const mpq_class b012 = (b01 + b12) / 2, b123 = (b12 + b23) / 2, b0123 = (b012 + b123) / 2;
    if (side(random) == 0) {
      cubic = left;
      truth = {truth[0], b01, b012, b0123};
    } else {
      cubic = right;
      truth = {b0123, b123, b23, truth[3]};
    }
  }
}

}  // namespace

TEST_CASE("D's rounded Bernstein coefficients stay within their bound through repeated halving", "[ccd][rounded]") {
  std::mt19937 random(7u);
  std::uniform_int_distribution<int> depth(0, 40);
  int inexact = 0, inexact_halving = 0;
  for (int i = 0; i < 2000; ++i) {
    INFO("query " << i);
    const RandomPiece piece = random_piece(random, 0);
    const RoundedQuery& rounded = piece.rounded;
    inexact += check_halving_path(random, rounded.d, exact_d(piece.query), depth(random), rounded.halving_error);
    // The halving alone: the rounded coefficients taken as exact, so only halving_error covers the errors.
    const RoundedCubic exactly_known{rounded.d.b, 0.0};
    std::array<mpq_class, 4> known;
    for (int j = 0; j < 4; ++j) known[j] = exact(rounded.d.b[j]);
    inexact_halving += check_halving_path(random, exactly_known, known, depth(random), rounded.halving_error);
  }
  CHECK(inexact > 5000);
  CHECK(inexact_halving > 5000);
}

TEST_CASE("queries at extreme scales get the unscaled query's answer", "[ccd][rounded]") {
  using clothcd::test::scaled;
  const CcdQuery crossing = clothcd::test::make_query(
      PairKind::VertexFace, {Vector3d(0.2, 0.3, 1.0), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)},
      {Vector3d(0.2, 0.3, -1.0), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)});
  REQUIRE(clothcd::ccd::detail::rounded_query(crossing));
  // Coordinates beyond 2^100: no rounded query, the exact tiers answer; tiny ones: the bounds' absolute terms may leave
  // the query to them.
  CHECK_FALSE(clothcd::ccd::detail::rounded_query(scaled(crossing, 0x1p120)));
  for (const double scale : {0x1p-400, 0x1p-1000, 0x1p120}) {
    const CcdQuery query = scaled(crossing, scale);
    const clothcd::ccd::CcdResult result = clothcd::ccd::continuous_collision(query, clothcd::test::exact_settings());
    CHECK(result.hit);
    CHECK(result.toi <= 0.5);
    CHECK(result.toi >= 0.5 - 1e-6);
  }
  const clothcd::ccd::CcdResult fast = clothcd::ccd::continuous_collision(crossing, clothcd::test::exact_settings());
  CHECK(fast.hit);
  CHECK(fast.toi <= 0.5);
  CHECK(fast.toi >= 0.5 - 1e-6);
}

TEST_CASE("the rounded tier's bounds stay normal numbers where W has exact zeros", "[ccd][rounded]") {
  // A flat cloth's pair: every z difference exactly 0 (subnormal products there cost a microcode assist each).
  const CcdQuery flat = clothcd::test::make_query(
      PairKind::EdgeEdge, {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, -0.5, 0), Vector3d(0.5, 0.5, 0)},
      {Vector3d(0, 0.1, 0), Vector3d(1, 0.1, 0), Vector3d(0.5, -0.4, 0), Vector3d(0.5, 0.6, 0)});
  const std::optional<RoundedQuery> rounded = clothcd::ccd::detail::rounded_query(flat);
  REQUIRE(rounded);
  const double smallest_normal = std::numeric_limits<double>::min();
  for (int d = 0; d < 3; ++d) {
    for (int m = 0; m < 4; ++m) {
      CHECK(rounded->point_error[d][m] >= smallest_normal);
      CHECK(rounded->magnitude[d][m] * rounded->magnitude[d][m] >= smallest_normal);
    }
  }
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) CHECK(clothcd::ccd::detail::cross_error(*rounded, a, b, k) >= smallest_normal);
  CHECK(rounded->d.error >= smallest_normal);
  CHECK(rounded->halving_error >= smallest_normal);
}
