// Ericson's closest points (geometry/pair_distance.hpp) in each Voronoi region of a triangle, on a
// degenerate triangle, and between segments (crossing, parallel, and reduced to points).
#include <catch2/catch.hpp>

#include "geometry/pair_distance.hpp"

using Eigen::Vector3d;
using namespace clothcd::geometry;

TEST_CASE("primitive distance: the closest point on a triangle in each region", "[geometry][distance]") {
  const Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  CHECK(closest_point_on_triangle(Vector3d(0.5, 0.5, 3), a, b, c).isApprox(Vector3d(0.5, 0.5, 0)));  // face
  CHECK(closest_point_on_triangle(Vector3d(-1, -1, 1), a, b, c) == a);                                // vertices
  CHECK(closest_point_on_triangle(Vector3d(3, -1, 0), a, b, c) == b);
  CHECK(closest_point_on_triangle(Vector3d(-1, 3, 0), a, b, c) == c);
  CHECK(closest_point_on_triangle(Vector3d(1, -1, 0), a, b, c).isApprox(Vector3d(1, 0, 0)));  // edges
  CHECK(closest_point_on_triangle(Vector3d(-1, 1, 0), a, b, c).isApprox(Vector3d(0, 1, 0)));
  CHECK(closest_point_on_triangle(Vector3d(2, 2, 0), a, b, c).isApprox(Vector3d(1, 1, 0)));
  CHECK(point_triangle_distance_squared(Vector3d(0.5, 0.5, 3), a, b, c) == Approx(9.0));
  // A triangle of three equal corners is its corner.
  CHECK(closest_point_on_triangle(Vector3d(1, 1, 1), b, b, b) == b);
}

TEST_CASE("primitive distance: segments", "[geometry][distance]") {
  // Crossing at a height of 1.
  const Vector3d x0(-1, 0, 0), x1(1, 0, 0), y0(0, -1, 1), y1(0, 1, 1);
  CHECK(segment_segment_distance_squared(x0, x1, y0, y1) == Approx(1.0));
  // Parallel, overlapping.
  CHECK(segment_segment_distance_squared(Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 2, 0), Vector3d(3, 2, 0)) ==
        Approx(4.0));
  // Endpoint to endpoint.
  CHECK(segment_segment_distance_squared(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 1, 0), Vector3d(3, 1, 0)) ==
        Approx(2.0));
  // Points.
  CHECK(segment_segment_distance_squared(Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(0, 3, 4), Vector3d(0, 3, 4)) ==
        Approx(25.0));
  CHECK(segment_segment_distance_squared(Vector3d(0, 1, 0), Vector3d(0, 1, 0), Vector3d(-1, 0, 0), Vector3d(1, 0, 0)) ==
        Approx(1.0));
}
