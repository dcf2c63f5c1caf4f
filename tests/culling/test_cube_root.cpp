// The features' vectorizable cube root against the C library's, on seeded random doubles of every magnitude.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "culling/cube_root.hpp"

using clothcd::learning::detail::cube_root;

namespace {

// Distance in units in the last place between two finite doubles of one sign.
std::uint64_t ulps_apart(double a, double b) {
  std::int64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x > y ? static_cast<std::uint64_t>(x - y) : static_cast<std::uint64_t>(y - x);
}

}  // namespace

TEST_CASE("cube_root is within 4 ulp of std::cbrt over every magnitude", "[learning][features]") {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> unit(-2.0, 2.0);
  std::uint64_t worst = 0;
  for (int i = 0; i < 400000; ++i) {
    std::uint64_t bits = rng();
    double x;
    std::memcpy(&x, &bits, sizeof x);  // any double, subnormals included
    if (i % 2 == 1) x = unit(rng);
    if (!std::isfinite(x)) continue;
    const double ours = cube_root(x);
    REQUIRE(std::signbit(ours) == std::signbit(x));
    CHECK(cube_root(-x) == -ours);
    worst = std::max(worst, ulps_apart(ours, std::cbrt(x)));
  }
  CHECK(worst <= 4);
}

TEST_CASE("cube_root of exact cubes, zeros, infinities and NaN", "[learning][features]") {
  for (int k = -200; k <= 200; ++k) CHECK(cube_root(static_cast<double>(k) * k * k) == k);
  CHECK(cube_root(0x1p-1074) == Approx(std::cbrt(0x1p-1074)).epsilon(1e-15));  // the smallest subnormal
  CHECK(cube_root(std::numeric_limits<double>::max()) == Approx(std::cbrt(std::numeric_limits<double>::max())).epsilon(1e-15));
  CHECK(cube_root(0.0) == 0.0);
  CHECK_FALSE(std::signbit(cube_root(0.0)));
  CHECK(std::signbit(cube_root(-0.0)));
  CHECK(cube_root(std::numeric_limits<double>::infinity()) == std::numeric_limits<double>::infinity());
  CHECK(cube_root(-std::numeric_limits<double>::infinity()) == -std::numeric_limits<double>::infinity());
  CHECK(std::isnan(cube_root(std::numeric_limits<double>::quiet_NaN())));
}
