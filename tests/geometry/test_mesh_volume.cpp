// Divergence-theorem volume on shapes of known volume; compactness tau.
#include <catch2/catch.hpp>

#include <cmath>

#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

TEST_CASE("Mesh volume of a box, moved and flipped", "[geometry][volume]") {
  TriangleMesh box = make_box(Eigen::Vector3d(1.0, 2.0, 0.5));
  CHECK(mesh_volume(box) == Approx(8.0));  // 2 x 4 x 1
  box.vertices.rowwise() += Eigen::RowVector3d(100, -50, 7);
  CHECK(mesh_volume(box) == Approx(8.0));
  box.faces.col(1).swap(box.faces.col(2));  // inside-out: the sign flips
  CHECK(mesh_volume(box) == Approx(-8.0));
  CHECK(compactness(16.0, box) == Approx(2.0));
}

TEST_CASE("Mesh volume of a UV sphere approaches 4/3 pi r^3 from below", "[geometry][volume]") {
  const double exact = 4.0 / 3.0 * M_PI * 8.0;
  const double coarse = mesh_volume(make_uv_sphere(2.0, 16, 8));
  const double fine = mesh_volume(make_uv_sphere(2.0, 128, 64));
  // An inscribed polyhedron: smaller than the ball, closer as it refines.
  CHECK(coarse < fine);
  CHECK(fine < exact);
  CHECK(fine == Approx(exact).epsilon(0.002));
}

TEST_CASE("Compactness needs a volume", "[geometry][volume]") {
  CHECK_THROWS_AS(compactness(1.0, make_grid(3, 3)), std::invalid_argument);
  TriangleMesh bad = make_box();
  bad.faces(2, 0) = -1;
  CHECK_THROWS_AS(mesh_volume(bad), std::invalid_argument);
}
