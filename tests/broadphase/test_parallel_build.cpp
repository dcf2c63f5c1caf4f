// Bvh::build and its refit on TBB tasks (BvhSettings::parallel) against the serial ones: the same tree, triangle
// order, owned primitives, boxes, packed boxes and volumes, bit for bit, on meshes large enough for the parallel split to run.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/swept_boxes.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;

namespace {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_packed(const PackedBoxes& a, const PackedBoxes& b) {
  if (a.size() != b.size()) return false;
  for (int j = 0; j < a.size(); ++j) {
    const PackedBox pa = a.at(j), pb = b.at(j);
    if (std::memcmp(&pa, &pb, sizeof pa) != 0) return false;
  }
  return true;
}

// Builds `mesh` moving to `end` serially and in parallel with `volume` nodes and checks both hierarchies are equal.
void check_parallel_equals_serial(const TriangleMesh& mesh, const Vertices& end, VolumeKind volume) {
  const BodyTopology topology = build_body_topology(mesh.faces, static_cast<int>(mesh.vertex_count()));
  SweptBoxes boxes;
  compute_swept_vertex_boxes(mesh.vertices, end, 0.0, boxes);
  BvhSettings settings;
  settings.volume = volume;
  settings.max_leaf_faces = 8;
  settings.parallel = false;
  Bvh serial(settings);
  serial.build(topology, boxes, mesh.vertices, end);
  settings.parallel = true;
  Bvh parallel(settings);
  parallel.build(topology, boxes, mesh.vertices, end);

  REQUIRE(serial.nodes().size() == parallel.nodes().size());
  for (std::size_t i = 0; i < serial.nodes().size(); ++i) {
    const BvhNode &a = serial.nodes()[i], &b = parallel.nodes()[i];
    INFO("node " << i);
    REQUIRE(a.right == b.right);
    REQUIRE(a.face_begin == b.face_begin);
    REQUIRE(a.face_end == b.face_end);
  }
  CHECK(serial.face_order() == parallel.face_order());
  CHECK(serial.owned_vertices() == parallel.owned_vertices());
  CHECK(serial.owned_edges() == parallel.owned_edges());
  CHECK(same_bits(serial.boxes(), parallel.boxes()));
  CHECK(same_bits(serial.ordered_face_boxes(), parallel.ordered_face_boxes()));
  CHECK(same_bits(serial.ordered_vertex_boxes(), parallel.ordered_vertex_boxes()));
  CHECK(same_bits(serial.ordered_edge_boxes(), parallel.ordered_edge_boxes()));
  CHECK(same_packed(serial.packed_face_boxes(), parallel.packed_face_boxes()));
  CHECK(same_packed(serial.packed_vertex_boxes(), parallel.packed_vertex_boxes()));
  CHECK(same_packed(serial.packed_edge_boxes(), parallel.packed_edge_boxes()));
  CHECK(same_packed(serial.packed_node_boxes(), parallel.packed_node_boxes()));
  CHECK(serial.looseness() == parallel.looseness());
  REQUIRE(serial.spheres().size() == parallel.spheres().size());
  for (std::size_t i = 0; i < serial.spheres().size(); ++i) {
    CHECK(serial.spheres()[i].radius == parallel.spheres()[i].radius);
    CHECK(serial.spheres()[i].center == parallel.spheres()[i].center);
  }
  REQUIRE(serial.obbs().size() == parallel.obbs().size());
  for (std::size_t i = 0; i < serial.obbs().size(); ++i) {
    CHECK(serial.obbs()[i].center == parallel.obbs()[i].center);
    CHECK(serial.obbs()[i].half_extents == parallel.obbs()[i].half_extents);
  }
}

}  // namespace

TEST_CASE("a hierarchy built on several threads equals the serial build, bit for bit", "[broadphase][parallel]") {
  std::mt19937 rng(20261126);
  const VolumeKind volume = GENERATE(VolumeKind::Aabb, VolumeKind::Sphere, VolumeKind::Obb);
  SECTION("a jittered cloth grid") {
    const TriangleMesh grid = make_grid(200, 100, 2.0, 1.0);  // 39,402 triangles: a parallel refit too
    check_parallel_equals_serial(grid, test::jitter(grid.vertices, 0.01, rng), volume);
  }
  SECTION("a random triangle soup with degenerate triangles") {
    const TriangleMesh soup = test::random_soup(6000, 20000, rng);
    check_parallel_equals_serial(soup, test::jitter(soup.vertices, 0.05, rng), volume);
  }
  SECTION("coincident triangles, split at the median") {
    TriangleMesh same = test::random_soup(3, 9000, rng);
    for (int f = 0; f < static_cast<int>(same.faces.rows()); ++f) same.faces.row(f) << 0, 1, 2;
    check_parallel_equals_serial(same, same.vertices, volume);
  }
}

TEST_CASE("a build with a non-finite box names the first such face, serial and parallel", "[broadphase][parallel]") {
  const TriangleMesh grid = make_grid(100, 50, 2.0, 1.0);  // 9,702 triangles: the parallel fill runs
  const BodyTopology topology = build_body_topology(grid.faces, static_cast<int>(grid.vertex_count()));
  Vertices end = grid.vertices;
  end(grid.faces(7000, 1), 2) = std::numeric_limits<double>::quiet_NaN();
  end(grid.faces(9000, 0), 0) = std::numeric_limits<double>::infinity();
  SweptBoxes boxes;
  compute_swept_vertex_boxes(grid.vertices, end, 0.0, boxes);
  int first = -1;  // the first face whose box has a non-finite centre
  for (int f = 0; f < static_cast<int>(grid.faces.rows()) && first < 0; ++f) {
    FlatBox b = boxes.vertices[grid.faces(f, 0)];
    b.expand(boxes.vertices[grid.faces(f, 1)]);
    b.expand(boxes.vertices[grid.faces(f, 2)]);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(b.min[k] + b.max[k])) first = f;
    }
  }
  REQUIRE(first >= 0);
  for (const bool parallel : {false, true}) {
    BvhSettings settings;
    settings.parallel = parallel;
    Bvh bvh(settings);
    CHECK_THROWS_WITH(bvh.build(topology, boxes, grid.vertices, end),
                      "bvh: face " + std::to_string(first) + " has a NaN or infinite box");
  }
}
