// The Morton order of QEM simplification against a bit-by-bit interleaving and a stable sort, on seeded random points,
// ties and points outside the unit cube.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "geometry/morton_order.hpp"

using clothcd::geometry::detail::morton_code;
using clothcd::geometry::detail::morton_order;

namespace {

// Bit b of axis a's 10-bit grid coordinate goes to bit 3 b + a, one bit at a time.
std::uint32_t reference_code(const Eigen::Vector3d& p) {
  std::uint32_t code = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double t = std::clamp(p[axis], 0.0, 1.0);
    const auto cell = static_cast<std::uint32_t>(t * 1023.0);
    for (int bit = 0; bit < 10; ++bit) code |= ((cell >> bit) & 1u) << (3 * bit + axis);
  }
  return code;
}

std::vector<int> reference_order(const std::vector<Eigen::Vector3d>& points) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return reference_code(points[size_t(a)]) < reference_code(points[size_t(b)]); });
  return order;
}

}  // namespace

TEST_CASE("morton_code interleaves the axes' bits like the bit-by-bit reference", "[morton]") {
  CHECK(morton_code({0, 0, 0}) == 0u);
  CHECK(morton_code({1, 1, 1}) == (1u << 30) - 1);
  CHECK(morton_code({1, 0, 0}) == 0x09249249u);
  CHECK(morton_code({-3, 2, 0.5}) == reference_code({0, 1, 0.5}));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-0.1, 1.1);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(coord(rng), coord(rng), coord(rng));
    REQUIRE(morton_code(p) == reference_code(p));
  }
}

TEST_CASE("morton_order matches a stable sort by the reference code, ties in input order", "[morton]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 22; ++trial) {
    // The last two trials are large: every digit of the radix sort's passes takes many values.
    const int n = trial < 20 ? std::uniform_int_distribution<int>(0, 300)(rng) : 50000;
    // A coarse grid makes many points share a code (ties); a fine one makes codes mostly distinct.
    const double steps = trial % 2 == 0 ? 4.0 : 1e6;
    std::uniform_int_distribution<int> cell(0, int(steps));
    std::vector<Eigen::Vector3d> points(static_cast<size_t>(n));
    for (auto& p : points) p = Eigen::Vector3d(cell(rng), cell(rng), cell(rng)) / steps;
    const std::vector<int> order = morton_order(points);
    REQUIRE(order == reference_order(points));
  }
}
