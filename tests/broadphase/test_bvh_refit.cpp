// Bvh::update_moved against Bvh::update: after random moves of a few (or many) vertices, refitting only what holds
// them must leave every box, packed box, sphere and the looseness exactly as a full refit does, and rebuild when it
// does.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/swept_boxes.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;

namespace {

bool same_bits(const void* a, const void* b, std::size_t bytes) { return bytes == 0 || std::memcmp(a, b, bytes) == 0; }

void check_same_boxes(const std::vector<FlatBox>& a, const std::vector<FlatBox>& b) {
  REQUIRE(a.size() == b.size());
  CHECK(same_bits(a.data(), b.data(), a.size() * sizeof(FlatBox)));
}

void check_same_packed(const PackedBoxes& a, const PackedBoxes& b) {
  REQUIRE(a.size() == b.size());
  for (int j = 0; j < a.size(); ++j) {
    const PackedBox pa = a.at(j), pb = b.at(j);
    CHECK(same_bits(&pa, &pb, sizeof(PackedBox)));
  }
}

void check_same_hierarchy(const Bvh& a, const Bvh& b) {
  CHECK(a.build_count() == b.build_count());
  CHECK(a.looseness() == b.looseness());
  check_same_boxes(a.boxes(), b.boxes());
  check_same_boxes(a.ordered_face_boxes(), b.ordered_face_boxes());
  check_same_boxes(a.ordered_vertex_boxes(), b.ordered_vertex_boxes());
  check_same_boxes(a.ordered_edge_boxes(), b.ordered_edge_boxes());
  check_same_packed(a.packed_face_boxes(), b.packed_face_boxes());
  check_same_packed(a.packed_vertex_boxes(), b.packed_vertex_boxes());
  check_same_packed(a.packed_edge_boxes(), b.packed_edge_boxes());
  check_same_packed(a.packed_node_boxes(), b.packed_node_boxes());
  REQUIRE(a.spheres().size() == b.spheres().size());
  for (std::size_t i = 0; i < a.spheres().size(); ++i) {
    CHECK(a.spheres()[i].radius == b.spheres()[i].radius);
    CHECK(a.spheres()[i].center == b.spheres()[i].center);
  }
}

}  // namespace

TEST_CASE("refitting only the moved vertices' boxes equals a full refit, bit for bit", "[broadphase][moved]") {
  const VolumeKind volume = GENERATE(VolumeKind::Aabb, VolumeKind::Sphere, VolumeKind::Obb);
  const double share = GENERATE(0.002, 0.05, 0.5);
  const TriangleMesh cloth = make_grid(21, 17, 1.0, 0.8);
  const BodyTopology topology = build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count()));
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> small(-0.01, 0.01);
  std::bernoulli_distribution pick(share);

  const Vertices start = cloth.vertices;
  Vertices end = start;
  for (Eigen::Index i = 0; i < end.size(); ++i) end.data()[i] += small(rng);
  BvhSettings settings;
  settings.volume = volume;
  settings.max_leaf_faces = 8;
  SweptBoxes boxes;
  compute_swept_vertex_boxes(start, end, 0.002, boxes);
  Bvh full(settings), partial(settings);
  full.build(topology, boxes, start, end);
  partial.build(topology, boxes, start, end);

  int rebuilds = 0;
  for (int call = 0; call < 12; ++call) {
    // A few vertices move; on the last calls far enough to loosen the hierarchy past its rebuild ratio.
    std::vector<std::uint8_t> moved(static_cast<std::size_t>(end.rows()), 0);
    const double reach = call < 9 ? 0.02 : 0.6;
    for (Eigen::Index v = 0; v < end.rows(); ++v) {
      if (!pick(rng)) continue;
      moved[static_cast<std::size_t>(v)] = 1;
      for (int k = 0; k < 3; ++k) end(v, k) += reach * small(rng) / 0.01;
    }
    compute_swept_vertex_boxes(start, end, 0.002, boxes);
    const BvhUpdate a = full.update(topology, boxes, start, end);
    const BvhUpdate b = partial.update_moved(topology, boxes, start, end, moved);
    CHECK(a == b);
    rebuilds += a == BvhUpdate::Rebuilt ? 1 : 0;
    check_same_hierarchy(full, partial);
  }
  if (share == 0.5) CHECK(rebuilds > 0);  // the rebuild rule fires the same way

  std::vector<std::uint8_t> wrong_size(3, 0);
  if (volume != VolumeKind::Obb) {
    CHECK_THROWS_AS(partial.update_moved(topology, boxes, start, end, wrong_size), std::invalid_argument);
  }
}
