// The convex hull at any scale: a sphere's points are all hull vertices, the triangulated hull has 2V - 4 faces, and
// every face points outwards.
#include <catch2/catch.hpp>

#include <cmath>

#include "clothcd/geometry/convex_hull.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;

TEST_CASE("the convex hull of a sphere is right from tiny to huge coordinates", "[geometry][hull]") {
  for (const double radius : {1e-200, 1e-100, 1.0, 1e100, 1e155, 1e170, 1e200, 1e300}) {
    INFO("radius " << radius);
    const TriangleMesh sphere = make_uv_sphere(radius, 8, 4);
    const geometry::ConvexHull hull = geometry::compute_convex_hull(sphere.vertices);
    CHECK_FALSE(hull.degenerate);
    CHECK(hull.vertex_indices.size() == static_cast<std::size_t>(sphere.vertex_count()));
    CHECK(hull.faces.rows() == 2 * sphere.vertex_count() - 4);
    // Outward: every point on the inner side of every face (in units of the radius, so nothing overflows).
    const Vertices unit = sphere.vertices / radius;
    for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
      const Eigen::Vector3d a = unit.row(hull.faces(f, 0)), b = unit.row(hull.faces(f, 1)), c = unit.row(hull.faces(f, 2));
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      CHECK((unit.rowwise() - a.transpose()).operator*(normal).maxCoeff() <= 1e-12);
    }
  }
}
