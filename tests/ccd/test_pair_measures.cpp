// The shared pair measures (ccd/pair_measures.hpp): the direction table holds the square roots the filters and
// the features computed before it existed, the signed margin keeps the per-pair tie rule, and the Bernstein
// coefficients bound the coplanarity cubic.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "ccd/pair_measures.hpp"

namespace {

namespace measures = clothcd::ccd::pair_measures;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("pair measures: eq. 10's directions are the rounded square roots", "[ccd][measures]") {
  const volatile double two = 2.0, three = 3.0, half = 0.5, third = 1.0 / 3.0;  // evaluated at run time
  for (const measures::ProjectionDirection& d : measures::kProjectionDirections) {
    const double count = d.s[0] + d.s[1] + d.s[2];
    CHECK(d.l1 == count);
    CHECK(same_bits(d.norm, count == 1.0 ? 1.0 : std::sqrt(count == 2.0 ? two : three)));
    const double unit = count == 1.0 ? 1.0 : std::sqrt(count == 2.0 ? half : third);
    for (std::size_t c = 0; c < 3; ++c) CHECK(same_bits(d.unit[c], d.s[c] == 0.0 ? 0.0 : unit));
  }
}

TEST_CASE("pair measures: the signed margin of one sign", "[ccd][measures]") {
  const double positive[] = {3.0, 1.0, 2.0};
  const double negative[] = {-3.0, -1.0, -2.0};
  const double mixed[] = {-3.0, 1.0, 2.0};
  CHECK(measures::same_sign_margin(positive, 3) == 1.0);
  CHECK(measures::same_sign_margin(negative, 3) == 1.0);
  CHECK(measures::same_sign_margin(mixed, 3) == -2.0);
  // Equal zeros: the first smallest and the last largest (std::minmax_element's choice).
  const double zeros[] = {0.0, -0.0};
  CHECK(same_bits(measures::same_sign_margin(zeros, 2), 0.0));
  const double zeros_reversed[] = {-0.0, 0.0};
  CHECK(same_bits(measures::same_sign_margin(zeros_reversed, 2), -0.0));
}

TEST_CASE("pair measures: the Bernstein coefficients bound the coplanarity cubic", "[ccd][measures]") {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    Eigen::Vector3d start[4], end[4];
    for (int k = 0; k < 4; ++k) {
      start[k] = {coordinate(random), coordinate(random), coordinate(random)};
      end[k] = {coordinate(random), coordinate(random), coordinate(random)};
    }
    const auto b = measures::coplanarity_bernstein(start, end);
    for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      Eigen::Vector3d x[4];
      for (int k = 0; k < 4; ++k) x[k] = (1.0 - t) * start[k] + t * end[k];
      const double d = (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]);
      const double s = 1.0 - t;
      const double bernstein = s * s * s * b[0] + 3 * s * s * t * b[1] + 3 * s * t * t * b[2] + t * t * t * b[3];
      CHECK(d == Approx(bernstein).margin(1e-12));
    }
  }
}
