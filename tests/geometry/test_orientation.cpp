// The exact orientation predicates against GMP on inputs where the filter is tested hardest: points within a few
// ulps of coplanar (or collinear), coordinates whose products underflow or overflow, and axes where all points agree.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/orientation.hpp"

using namespace clothcd::geometry;

namespace {

using V = Eigen::Vector3d;

V random_point(std::mt19937_64& random, double scale) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return scale * V(unit(random), unit(random), unit(random));
}

// s moved by `steps` ulps along each axis.
V ulps(V s, const std::array<int, 3>& steps) {
  for (int k = 0; k < 3; ++k) {
    for (int n = 0; n < std::abs(steps[k]); ++n) s[k] = std::nextafter(s[k], steps[k] > 0 ? INFINITY : -INFINITY);
  }
  return s;
}

}  // namespace

TEST_CASE("orient3d is exact within a few ulps of coplanar", "[geometry][orientation]") {
  std::mt19937_64 random(77);
  std::uniform_real_distribution<double> weight(-0.5, 1.5);
  std::uniform_int_distribution<int> step(-3, 3);
  int wrong = 0, zero = 0, nonzero = 0;
  for (const double scale : {1e-6, 1.0, 1e6}) {
    for (int n = 0; n < 4000; ++n) {
      const V offset = n % 2 ? random_point(random, 100.0 * scale) : V::Zero();
      const V p = offset + random_point(random, scale), q = offset + random_point(random, scale);
      const V r = offset + random_point(random, scale);
      const V s = ulps(p + weight(random) * (q - p) + weight(random) * (r - p), {step(random), step(random), 0});
      const int exact = gmp_orient3d(p, q, r, s);
      wrong += orient3d(p, q, r, s).sign != exact;
      (exact == 0 ? zero : nonzero) += 1;
    }
  }
  CHECK(wrong == 0);
  CHECK(nonzero > 1000);
}

TEST_CASE("orient2d is exact within a few ulps of collinear", "[geometry][orientation]") {
  std::mt19937_64 random(78);
  std::uniform_real_distribution<double> weight(-0.5, 1.5);
  std::uniform_int_distribution<int> step(-3, 3), axis(0, 2);
  int wrong = 0;
  for (const double scale : {1e-6, 1.0, 1e6}) {
    for (int n = 0; n < 4000; ++n) {
      const V offset = n % 2 ? random_point(random, 100.0 * scale) : V::Zero();
      const V p = offset + random_point(random, scale), q = offset + random_point(random, scale);
      const V r = ulps(p + weight(random) * (q - p), {step(random), step(random), step(random)});
      const int drop = axis(random);
      wrong += orient2d(p, q, r, drop).sign != gmp_orient2d(p, q, r, drop);
    }
  }
  CHECK(wrong == 0);
}

TEST_CASE("the orientation predicates stay exact where products underflow or overflow", "[geometry][orientation]") {
  std::mt19937_64 random(79);
  std::uniform_int_distribution<int> step(-2, 2);
  int wrong3 = 0, wrong2 = 0;
  // Uniformly tiny, uniformly huge, and one axis tiny against the others.
  // Two axes near 2^-537 put the products of the filter's 2x2 minors around the smallest subnormal.
  const std::array<V, 6> scales = {V::Constant(1e-160), V::Constant(1e-300),        V::Constant(1e150),
                                   V(1e-200, 1.0, 1.0), V(1.0, 0x1p-537, 0x1p-537), V::Constant(0x1p-537)};
  for (const V& scale : scales) {
    for (int n = 0; n < 2000; ++n) {
      const V p = random_point(random, 1.0).cwiseProduct(scale), q = random_point(random, 1.0).cwiseProduct(scale);
      const V r = random_point(random, 1.0).cwiseProduct(scale);
      const V s = ulps(0.5 * (p + q) + 0.25 * (r - p), {step(random), step(random), step(random)});
      wrong3 += orient3d(p, q, r, s).sign != gmp_orient3d(p, q, r, s);
      wrong2 += orient2d(p, q, s, n % 3).sign != gmp_orient2d(p, q, s, n % 3);
    }
  }
  CHECK(wrong3 == 0);
  CHECK(wrong2 == 0);
}

TEST_CASE("points sharing a coordinate orient exactly to zero", "[geometry][orientation]") {
  const V p(0.1, 7.0, 0.3), q(0.7, 7.0, -0.2), r(-0.4, 7.0, 0.9), s(1e-300, 7.0, 5.0);
  CHECK(orient3d(p, q, r, s).sign == 0);
  const V above(0.2, 7.0 + 1e-15, 0.1);
  CHECK(gmp_orient3d(p, q, r, above) != 0);
  CHECK(orient3d(p, q, r, above).sign == gmp_orient3d(p, q, r, above));
  CHECK(orient2d(p, q, r, 1).sign != 0);
  CHECK(orient2d(p, q, r, 0).sign == 0);
}

TEST_CASE("orient3d's permanent bound does not decide where underflow can flip the rounded sign",
          "[geometry][orientation]") {
  // The three products d_k n_k are 0.625, 0.625 and -1.375 times 2^-1074: rounded to the subnormal grid they sum to
  // +2^-1074, exactly they sum to -0.125 2^-1074 (a permanent far below 2^-950).
  const V p = V::Zero(), q(0x1p-300, 0.0, -0x1p-300), r(0.0, 0x1p-300, -0x1p-300);
  const V s = 0x1p-474 * V(0.625, 0.625, -1.375);
  REQUIRE(gmp_orient3d(p, q, r, s) == -1);
  CHECK(orient3d(p, q, r, s).sign == -1);
  // The cofactors are 0.625, 0.6875 and 1.375 times 2^-1074, all rounded to 2^-1074, then multiplied by d = 2^600
  // (1, 1, -1): the permanent 3 2^-474 is large, but not against the largest axis maximum 2^600.
  const V e1(11.0 * 0x1p-540, 0.0, -5.0 * 0x1p-540), e2(0.0, 0x1p-537, -0x1p-538), d = 0x1p600 * V(1.0, 1.0, -1.0);
  REQUIRE(gmp_orient3d(p, e1, e2, d) == -1);
  CHECK(orient3d(p, e1, e2, d).sign == -1);
}
