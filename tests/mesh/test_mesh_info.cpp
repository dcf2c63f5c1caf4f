// Mesh summary facts on small hand-made meshes whose answers are known.
#include <catch2/catch.hpp>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_info.hpp"

TEST_CASE("two separate boxes are two watertight components", "[mesh][info]") {
  const auto box = clothcd::make_box();
  clothcd::TriangleMesh two;
  two.vertices.resize(16, 3);
  two.vertices << box.vertices, (box.vertices.rowwise() + Eigen::RowVector3d(5, 0, 0));
  two.faces.resize(24, 3);
  two.faces << box.faces, (box.faces.array() + 8).matrix();
  const auto info = clothcd::compute_mesh_info(two);
  CHECK(info.components == 2);
  CHECK(info.watertight);
  CHECK(info.bbox_min.isApprox(Eigen::Vector3d(-1, -1, -1)));
  CHECK(info.bbox_max.isApprox(Eigen::Vector3d(6, 1, 1)));
}

TEST_CASE("a flipped face breaks watertightness, a third face on an edge is non-manifold", "[mesh][info]") {
  auto box = clothcd::make_box();
  std::swap(box.faces(0, 1), box.faces(0, 2));
  CHECK_FALSE(clothcd::compute_mesh_info(box).watertight);

  auto fin = clothcd::make_box();
  fin.vertices.conservativeResize(9, 3);
  fin.vertices.row(8) << 0, 0, 5;
  fin.faces.conservativeResize(13, 3);
  fin.faces.row(12) << 0, 1, 8;  // shares edge 0-1 with two box faces
  const auto info = clothcd::compute_mesh_info(fin);
  CHECK(info.non_manifold_edges == 1);
  CHECK_FALSE(info.watertight);
}

TEST_CASE("an empty mesh has counts of 0 and an empty box", "[mesh][info]") {
  const clothcd::MeshInfo info = clothcd::compute_mesh_info(clothcd::TriangleMesh{});
  CHECK(info.vertices == 0);
  CHECK(info.faces == 0);
  CHECK(info.components == 0);
  CHECK_FALSE(info.watertight);
  CHECK((info.bbox_min.array() > info.bbox_max.array()).all());
}
