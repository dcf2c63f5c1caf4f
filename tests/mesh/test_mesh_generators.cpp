// Generated meshes: the paper's cloth sizes, closed and outward-facing spheres, boxes and the fish.
#include <catch2/catch.hpp>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_info.hpp"

namespace {

/// Signed volume by the divergence theorem: positive when the closed surface faces outwards.
double signed_volume(const clothcd::TriangleMesh& mesh) {
  double six_volume = 0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

}  // namespace

TEST_CASE("the paper's cloths have the paper's vertex and triangle counts", "[mesh][generators]") {
  // Table 6 of the paper: A 400 / 722, B 900 / 1682, C 2500 / 4802.
  CHECK(clothcd::make_paper_cloth('A').vertex_count() == 400);
  CHECK(clothcd::make_paper_cloth('A').face_count() == 722);
  CHECK(clothcd::make_paper_cloth('B').face_count() == 1682);
  CHECK(clothcd::make_paper_cloth('C').vertex_count() == 2500);
  CHECK(clothcd::make_paper_cloth('C').face_count() == 4802);
  CHECK_THROWS_AS(clothcd::make_paper_cloth('D'), std::invalid_argument);
}

TEST_CASE("a grid is one flat open sheet facing +y", "[mesh][generators]") {
  const auto grid = clothcd::make_grid(7, 4, 3.0, 2.0);
  const auto info = clothcd::compute_mesh_info(grid);
  CHECK(info.faces == 2 * 6 * 3);
  CHECK(info.components == 1);
  CHECK_FALSE(info.watertight);
  CHECK(info.boundary_edges == 2 * (6 + 3));
  CHECK(info.surface_area == Approx(6.0));
  for (Eigen::Index f = 0; f < grid.face_count(); ++f) {
    const Eigen::Vector3d a = grid.vertices.row(grid.faces(f, 0)), b = grid.vertices.row(grid.faces(f, 1)),
                          c = grid.vertices.row(grid.faces(f, 2));
    CHECK((b - a).cross(c - a).y() > 0);
  }
  CHECK_THROWS_AS(clothcd::make_grid(1, 5), std::invalid_argument);
  CHECK_THROWS_AS(clothcd::make_grid(5, 5, 0.0, 1.0), std::invalid_argument);
}

TEST_CASE("closed generated solids are watertight and face outwards", "[mesh][generators]") {
  const auto sphere = clothcd::make_uv_sphere(1.0, 48, 24);
  CHECK(clothcd::compute_mesh_info(sphere).watertight);
  // A fine UV sphere's volume approaches 4/3 pi from below.
  CHECK(signed_volume(sphere) == Approx(4.18879).epsilon(0.02));

  const auto box = clothcd::make_box(Eigen::Vector3d(1, 2, 3));
  CHECK(clothcd::compute_mesh_info(box).watertight);
  CHECK(signed_volume(box) == Approx(48.0));

  const auto fish = clothcd::make_fish();
  const auto info = clothcd::compute_mesh_info(fish);
  CHECK(info.watertight);
  CHECK(info.degenerate_faces == 0);
  CHECK(signed_volume(fish) > 0);
}
