// The separating-direction rejection of the pair distances (geometry/pair_distance_separation.hpp) against the GMP
// reference: coplanar pairs, where neither the plane nor the line distance rejects, exactly d apart and one unit in the
// last place either side along the separating direction, and seeded random nearly flat neighbours (a long edge or
// a wide triangle and a point or edge a small gap beside it) asked at their own distance rounded and up to two units in
// the last place either side, where a bound that ignored the projections' rounding error would reject pairs within d.
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

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The pair asked at d, one unit in the last place either side, with the expected membership at d.
void check_around(bool vertex_face, const Points& x, double d, bool within_at_d) {
  CHECK(check_pair(vertex_face, x, d) == within_at_d);
  CHECK(check_pair(vertex_face, x, std::nextafter(d, kInfinity)));
  CHECK_FALSE(check_pair(vertex_face, x, std::nextafter(d, 0.0)));
}

// x with coordinate `axis` of x[which] moved one unit in the last place towards `to`.
Points nudged(Points x, int which, int axis, double to) {
  x[which][axis] = std::nextafter(x[which][axis], to);
  return x;
}

// The distance of a pair, rounded.
double rounded_distance(bool vertex_face, const Points& x) {
  return clothcd::geometry::rational::square_root(clothcd::test::reference(vertex_face, x).squared_distance);
}

}  // namespace

TEST_CASE("pair distance: coplanar pairs exactly d apart along the separating direction", "[pair-distance]") {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  // Beside an edge (0.5 below edge t0 t1) and beside a vertex ((3, 4) from t1), in the triangle's plane.
  for (const Points& x : {Points{Vector3d(0.25, -0.5, 0), t0, t1, t2}, Points{Vector3d(4, -4, 0), t0, t1, t2}}) {
    const double d = x[0].x() == 4 ? 5.0 : 0.5;
    check_around(true, x, d, false);
    // One unit in the last place nearer (within d) and farther (not within) along the direction.
    CHECK(check_pair(true, nudged(x, 0, 1, 0.0), d));
    CHECK_FALSE(check_pair(true, nudged(x, 0, 1, -kInfinity), d));
  }
  // Edge-edge in one plane: parallel side by side, and a vertex 0.5 beside the other edge's interior.
  const Points parallel{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.25, 0.5, 0), Vector3d(1.25, 0.5, 0)};
  const Points beside{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0.5, 0), Vector3d(0.75, 2, 0)};
  for (const Points& x : {parallel, beside}) {
    check_around(false, x, 0.5, false);
    CHECK(check_pair(false, nudged(x, 2, 1, 0.0), 0.5));
    CHECK_FALSE(check_pair(false, nudged(x, 2, 1, kInfinity), 0.5));
  }
}

TEST_CASE("pair distance: random nearly flat neighbours at their own distance", "[pair-distance]") {
  std::mt19937_64 rng(20240613);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto any = [&] { return Vector3d(unit(rng), unit(rng), unit(rng)); };
  for (int i = 0; i < 3000; ++i) {
    // A random plane through a random offset, the gap from 1e-2 to 1e-8 of the primitives' size.
    const Vector3d offset = 3.0 * any(), u = any().normalized(), v = u.cross(any()).normalized();
    const double gap = std::pow(10.0, -2 - (i % 7)), flatness = (i % 3) * 1e-3 * gap;
    const auto at = [&](double x, double y) { return Vector3d(offset + x * u + y * v + flatness * any()); };
    const bool vertex_face = i % 2 == 0;
    const double along = 0.5 * (unit(rng) + 1.0);
    // Vertex-face: the point beside edge t0 t1 (or beside vertex t0); edge-edge: b0 beside a's interior, b turning
    // slowly away from a.
    const Points x = vertex_face ? Points{at(i % 4 == 0 ? -gap : along, -gap), at(0, 0), at(1, 0), at(unit(rng), 1)}
                                 : Points{at(0, 0), at(1, 0), at(along, gap), at(along + unit(rng), gap + (i % 4) * gap)};
    // The rounded distance is within one unit in the last place of the exact one: two either side straddle it.
    const double d = rounded_distance(vertex_face, x);
    const double below = std::nextafter(d, 0.0), above = std::nextafter(d, kInfinity);
    CHECK_FALSE(check_pair(vertex_face, x, std::nextafter(below, 0.0)));
    for (double near : {below, d, above}) check_pair(vertex_face, x, near);
    CHECK(check_pair(vertex_face, x, std::nextafter(above, kInfinity)));
  }
}
