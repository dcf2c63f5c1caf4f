// The expansion stage of the orientation predicates against GMP: it decides, exactly, every input whose coordinates
// are in its range (nearly coplanar or collinear points, with exact and with inexact differences, and exactly
// coplanar ones) and none outside it; and the predicates stay exact on both sides of the range's ends, where a wider
// range would let products underflow or overflow.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/expansion_orientation.hpp"
#include "geometry/orientation.hpp"

using namespace clothcd::geometry;

namespace {

using V = Eigen::Vector3d;

V random_point(std::mt19937_64& random, double scale) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return scale * V(unit(random), unit(random), unit(random));
}

// Four points within rounding of one plane (s rounded from an affine combination of p, q, r), around `offset` times
// the scale.
std::array<V, 4> nearly_coplanar(std::mt19937_64& random, double scale, double offset) {
  std::uniform_real_distribution<double> weight(-0.5, 1.5);
  const V center = offset * scale * V(1.0, -0.75, 0.5);
  const V p = center + random_point(random, scale), q = center + random_point(random, scale);
  const V r = center + random_point(random, scale);
  return {p, q, r, V(p + weight(random) * (q - p) + weight(random) * (r - p))};
}

bool in_range(const std::array<V, 4>& points) {
  for (const V& p : points) {
    for (int k = 0; k < 3; ++k) {
      const double x = std::abs(p[k]);
      if (x != 0.0 && (x < detail::kExpansionSmallest || x > detail::kExpansionLargest)) return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("expansion orient3d and orient2d decide exactly in their range and not outside", "[geometry][orientation]") {
  std::mt19937_64 random(90);
  int wrong = 0, decided = 0, outside = 0, misjudged_range = 0;
  for (const double scale : {0x1p-310, 0x1p-298, 1e-40, 1e-3, 1.0, 1e3, 1e40, 0x1p297, 0x1p305}) {
    for (const double offset : {0.0, 4.0, 1e3}) {
      for (int n = 0; n < 400; ++n) {
        const std::array<V, 4> x = nearly_coplanar(random, scale, offset);
        const std::optional<int> sign3 = detail::expansion_orient3d(x[0], x[1], x[2], x[3]);
        const std::optional<int> sign2 = detail::expansion_orient2d(x[0], x[1], x[3], n % 3);
        // orient2d reads two coordinates only: its range test is checked where it has to decide.
        const bool inside = in_range(x);
        misjudged_range += sign3.has_value() != inside || (inside && !sign2);
        if (sign3) wrong += *sign3 != gmp_orient3d(x[0], x[1], x[2], x[3]);
        if (sign2) wrong += *sign2 != gmp_orient2d(x[0], x[1], x[3], n % 3);
        decided += sign3.has_value();
        outside += !inside;
      }
    }
  }
  CHECK(wrong == 0);
  CHECK(misjudged_range == 0);
  CHECK(decided > 5000);
  CHECK(outside > 500);
}

TEST_CASE("expansion orient3d finds exact zeros on integer grids", "[geometry][orientation]") {
  std::mt19937_64 random(91);
  std::uniform_int_distribution<int> coordinate(-1000, 1000), weight(-3, 3);
  int wrong = 0, zero = 0;
  for (const int exponent : {-290, -30, 0, 30, 280}) {
    const double unit = std::ldexp(1.0, exponent);
    for (int n = 0; n < 500; ++n) {
      const auto grid = [&] { return V(coordinate(random), coordinate(random), coordinate(random)); };
      const V p = grid(), q = grid(), r = grid();
      // s in the plane of p, q, r, or one unit off it.
      const V s = p + weight(random) * (q - p) + weight(random) * (r - p) + V(0.0, 0.0, n % 2);
      const std::optional<int> sign = detail::expansion_orient3d(unit * p, unit * q, unit * r, unit * s);
      wrong += !sign || *sign != gmp_orient3d(unit * p, unit * q, unit * r, unit * s);
      zero += sign == 0;
    }
  }
  CHECK(wrong == 0);
  CHECK(zero > 1000);
}

TEST_CASE("the orientation predicates stay exact on both sides of the expansion range's ends",
          "[geometry][orientation]") {
  // Just outside the range, products of three coordinates underflow (below 2^-1074 in their low bits) or overflow:
  // were the range wider, the expansions would lose the nearly coplanar points' sign there.
  std::mt19937_64 random(92);
  int wrong3 = 0, wrong2 = 0;
  for (const double scale : {0x1p-290, 0x1p-320, 0x1p-345, 0x1p-370, 0x1p-450, 0x1p290, 0x1p320, 0x1p345}) {
    for (int n = 0; n < 1000; ++n) {
      const auto [p, q, r, s] = nearly_coplanar(random, scale, 2.0);
      wrong3 += exact_orient3d(p, q, r, s) != gmp_orient3d(p, q, r, s);
      wrong3 += orient3d(p, q, r, s).sign != gmp_orient3d(p, q, r, s);
      wrong2 += exact_orient2d(p, q, s, n % 3) != gmp_orient2d(p, q, s, n % 3);
    }
  }
  CHECK(wrong3 == 0);
  CHECK(wrong2 == 0);
}

TEST_CASE("the orientation predicates are exact on ulp-sized simplices near the expansion range's lower end",
          "[geometry][orientation]") {
  // Corners one ulp apart at the corner (A, A, A): the determinants are ulp^3 and ulp^2, the smallest products of
  // such coordinates, which underflow (to zero) a little below the range.
  for (const int exponent : {-299, -302, -306, -310, -320, -340, -400, -500, -600}) {
    const double a = std::ldexp(1.0, exponent), ulp = std::ldexp(1.0, exponent - 52);
    const V p = V::Constant(a);
    const V q = p + V(ulp, 0.0, 0.0), r = p + V(0.0, ulp, 0.0), s = p + V(0.0, 0.0, ulp);
    INFO("corner 2^" << exponent);
    CHECK(gmp_orient3d(p, q, r, s) == 1);
    CHECK(exact_orient3d(p, q, r, s) == 1);
    CHECK(orient3d(p, q, r, s).sign == 1);
    CHECK(exact_orient2d(p, q, r, 2) == 1);
    CHECK(orient2d(p, q, r, 2).sign == 1);
  }
  // The range's end itself: decided on expansions.
  const V p = V::Constant(0x1p-299), x(0x1p-351, 0.0, 0.0), y(0.0, 0x1p-351, 0.0), z(0.0, 0.0, 0x1p-351);
  CHECK(detail::expansion_orient3d(p, p + x, p + y, p + z) == 1);
}
