// The exact pair distances (geometry/pair_distance.hpp) against the GMP reference on seeded random pairs at scales
// from 1e-6 to 1e6, generic and degenerate (repeated, collinear, coplanar points, a point on or near the other
// primitive, parallel and nearly parallel segments, nearly collinear triangles), each asked at its own distance
// rounded, one unit in the last place below and above it, and at distances around the primitives' size.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/rational_vector.hpp"
#include "pair_distance_checks.hpp"

namespace {

using clothcd::test::check_pair;
using clothcd::test::Points;
using Eigen::Vector3d;

struct RandomPairs {
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> unit{-1.0, 1.0};
  explicit RandomPairs(std::uint64_t seed) : rng(seed) {}
  Vector3d any() { return Vector3d(unit(rng), unit(rng), unit(rng)); }
  // Four points of size `scale` about an offset of a few sizes; `shape` picks a degeneracy.
  Points four(int shape, double scale) {
    const Vector3d offset = 4.0 * scale * any();
    Points x{any(), any(), any(), any()};
    switch (shape) {
      case 1:  // repeated point
        x[2] = x[1];
        break;
      case 2:  // collinear (rounded)
        x[3] = x[1] + 0.375 * (x[2] - x[1]);
        break;
      case 3:  // coplanar
        for (auto& y : x) y.z() = 0.25;
        break;
      case 4:  // on the other primitive (rounded)
        x[0] = x[1] + 0.25 * (x[2] - x[1]) + 0.5 * (x[3] - x[1]);
        break;
      case 5:  // parallel (rounded)
        x[3] = x[2] + (x[1] - x[0]);
        break;
      case 6:  // small against large
        x[0] *= 0.01;
        x[1] *= 0.01;
        break;
      case 7:  // near it
        x[0] = x[1] + 0.25 * (x[2] - x[1]) + 0.5 * (x[3] - x[1]) + 1e-3 * x[0];
        break;
      case 8:  // near an edge of it
        x[0] = x[1] + 0.5 * (x[2] - x[1]) + 1e-3 * x[0];
        break;
      case 9:  // nearly parallel
        x[3] = x[2] + (x[1] - x[0]) + 1e-3 * x[3];
        break;
      case 10:  // closer to parallel
        x[3] = x[2] + (x[1] - x[0]) + 1e-6 * x[3];
        break;
      case 11:  // nearly collinear
        x[3] = x[1] + 0.375 * (x[2] - x[1]) + 1e-6 * x[3];
        break;
      default:
        break;
    }
    for (auto& y : x) y = offset + scale * y;
    return x;
  }
};

void run(bool vertex_face, std::uint64_t seed, int count) {
  RandomPairs random(seed);
  int within = 0;
  for (int i = 0; i < count; ++i) {
    const double scale = std::pow(10.0, -6 + 3 * (i % 5));
    const Points x = random.four(i % 12, scale);
    const double distance =
        clothcd::geometry::rational::square_root(clothcd::test::reference(vertex_face, x).squared_distance);
    for (double d :
         {distance, std::nextafter(distance, 0.0), std::nextafter(distance, 1e300), 0.5 * scale, 2 * scale}) {
      if (d > 0.0) within += check_pair(vertex_face, x, d);
    }
  }
  CHECK(within > count);  // both outcomes are exercised
}

}  // namespace

TEST_CASE("pair distance: random point-triangle pairs against the exact reference", "[pair-distance]") {
  run(true, 20240611, 6000);
}

TEST_CASE("pair distance: random segment pairs against the exact reference", "[pair-distance]") {
  run(false, 20240612, 6000);
}
