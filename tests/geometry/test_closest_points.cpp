// Closest points of a point and a triangle and of two segments, against a dense parameter grid on seeded random and
// degenerate primitives: the returned points lie on the primitives, their distance is the returned distance (so it is
// at least the true minimum), and it is never above the best grid sample (an upper bound of the true minimum).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "geometry/pair_distance.hpp"

namespace {

using clothcd::geometry::ClosestPoints;
using clothcd::geometry::point_triangle_closest;
using clothcd::geometry::segment_segment_closest;
using Eigen::Vector3d;

constexpr int kGrid = 160;

double grid_point_triangle(const Vector3d& p, const Vector3d& t0, const Vector3d& t1, const Vector3d& t2) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kGrid; ++i) {
    for (int j = 0; i + j <= kGrid; ++j) {
      const double u = static_cast<double>(i) / kGrid, v = static_cast<double>(j) / kGrid;
      best = std::min(best, (p - (t0 + u * (t1 - t0) + v * (t2 - t0))).norm());
    }
  }
  return best;
}

double grid_segments(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kGrid; ++i) {
    for (int j = 0; j <= kGrid; ++j) {
      const double s = static_cast<double>(i) / kGrid, u = static_cast<double>(j) / kGrid;
      best = std::min(best, ((a0 + s * (a1 - a0)) - (b0 + u * (b1 - b0))).norm());
    }
  }
  return best;
}

// Random points in the unit cube, with degenerate arrangements mixed in: repeated points, collinear triples, points
// in one plane, and a point on the other primitive.
struct Shapes {
  std::mt19937 rng;
  std::uniform_real_distribution<double> unit{-1.0, 1.0};
  explicit Shapes(unsigned seed) : rng(seed) {}
  Vector3d any() { return Vector3d(unit(rng), unit(rng), unit(rng)); }
  // Four points; case `shape` picks the degeneracy.
  std::array<Vector3d, 4> four(int shape) {
    std::array<Vector3d, 4> x{any(), any(), any(), any()};
    switch (shape) {
      case 1: x[2] = x[1]; break;                                  // repeated point
      case 2: x[3] = x[1] + 0.37 * (x[2] - x[1]); break;           // collinear
      case 3: for (auto& y : x) y.z() = 0.25; break;                // coplanar
      case 4: x[0] = x[1] + 0.3 * (x[2] - x[1]) + 0.2 * (x[3] - x[1]); break;  // on the other primitive
      case 5: x[3] = x[2] + (x[1] - x[0]); break;                  // parallel segments
      default: break;
    }
    return x;
  }
};

void check_consistent(const ClosestPoints& c, double grid_best, double extent) {
  REQUIRE(std::isfinite(c.distance));
  CHECK(c.distance == Approx((c.first - c.second).norm()).margin(1e-12 * extent));
  CHECK(c.distance <= grid_best + 1e-12 * extent);
}

}  // namespace

TEST_CASE("point-triangle closest points match a dense grid", "[geometry][closest]") {
  Shapes shapes(61);
  for (int trial = 0; trial < 600; ++trial) {
    const auto x = shapes.four(trial % 6 == 5 ? 0 : trial % 6);
    const ClosestPoints c = point_triangle_closest(x[0], x[1], x[2], x[3]);
    const double w1 = c.parameters[0], w2 = c.parameters[1];
    REQUIRE(w1 >= 0.0);
    REQUIRE(w2 >= 0.0);
    REQUIRE(w1 + w2 <= 1.0 + 1e-12);
    CHECK((c.first - x[0]).norm() == 0.0);
    CHECK((c.second - (x[1] + w1 * (x[2] - x[1]) + w2 * (x[3] - x[1]))).norm() <= 1e-12);
    check_consistent(c, grid_point_triangle(x[0], x[1], x[2], x[3]), 4.0);
  }
}

TEST_CASE("segment-segment closest points match a dense grid", "[geometry][closest]") {
  Shapes shapes(67);
  for (int trial = 0; trial < 600; ++trial) {
    const auto x = shapes.four(trial % 6);
    const ClosestPoints c = segment_segment_closest(x[0], x[1], x[2], x[3]);
    const double s = c.parameters[0], u = c.parameters[1];
    REQUIRE(s >= 0.0);
    REQUIRE(s <= 1.0);
    REQUIRE(u >= 0.0);
    REQUIRE(u <= 1.0);
    CHECK((c.first - (x[0] + s * (x[1] - x[0]))).norm() <= 1e-12);
    CHECK((c.second - (x[2] + u * (x[3] - x[2]))).norm() <= 1e-12);
    check_consistent(c, grid_segments(x[0], x[1], x[2], x[3]), 4.0);
  }
}
