// CollisionDetector: its collisions are exactly those of the exact CCD run on every primitive pair (no broad phase,
// no filter), for every hierarchy kind and culling mode; input validation; moving obstacles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <random>
#include <tuple>

#include <tbb/global_control.h>

#include "broadphase/body_topology.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/cloth_over_sphere.hpp"
#include "detection/same_collisions.hpp"

using namespace clothcd;

namespace {

using Key = std::tuple<int, int, int, int, int, int, int, int, int>;

Key key_of(const Collision& c) {
  return {static_cast<int>(c.kind), c.vertices[0].body, c.vertices[0].vertex, c.vertices[1].body, c.vertices[1].vertex,
          c.vertices[2].body,       c.vertices[2].vertex, c.vertices[3].body, c.vertices[3].vertex};
}

struct Frame {
  const Vertices* start;
  const Vertices* end;
};

ccd::CcdQuery query_of(PairKind kind, const std::array<VertexRef, 4>& refs, const std::vector<Frame>& frames) {
  ccd::CcdQuery q;
  q.kind = kind;
  for (int k = 0; k < 4; ++k) {
    q.start[k] = frames[refs[k].body].start->row(refs[k].vertex).transpose();
    q.end[k] = frames[refs[k].body].end->row(refs[k].vertex).transpose();
  }
  return q;
}

// Every vertex-face and edge-edge pair of cloth (body 0) vs itself and vs the obstacle (body 1) through the exact CCD.
std::vector<Key> all_pairs_reference(const TriangleMesh& cloth, const TriangleMesh& obstacle,
                                     const std::vector<Frame>& frames, double thickness) {
  const broadphase::BodyTopology topo[2] = {
      broadphase::build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count())),
      broadphase::build_body_topology(obstacle.faces, static_cast<int>(obstacle.vertex_count()))};
  const ccd::CcdSettings settings{thickness};
  std::vector<Key> keys;
  auto test = [&](PairKind kind, const std::array<VertexRef, 4>& refs) {
    const ccd::CcdQuery q = query_of(kind, refs, frames);
    if (ccd::continuous_collision(q, settings).hit) {
      Collision c;
      c.kind = kind;
      c.vertices = refs;
      keys.push_back(key_of(c));
    }
  };
  const std::pair<int, int> body_pairs[3] = {{0, 0}, {0, 1}, {1, 0}};
  for (auto [vb, fb] : body_pairs) {
    for (int v = 0; v < topo[vb].vertex_count; ++v) {
      for (int f = 0; f < topo[fb].face_count(); ++f) {
        if (vb == fb && topo[vb].face_has_vertex(f, v)) continue;
        const auto& faces = topo[fb].faces;
        test(PairKind::VertexFace, {VertexRef{vb, v}, VertexRef{fb, faces(f, 0)}, VertexRef{fb, faces(f, 1)},
                                    VertexRef{fb, faces(f, 2)}});
      }
    }
  }
  for (auto [ba, bb] : {std::pair<int, int>{0, 0}, std::pair<int, int>{0, 1}}) {
    for (int e = 0; e < topo[ba].edge_count(); ++e) {
      for (int g = ba == bb ? e + 1 : 0; g < topo[bb].edge_count(); ++g) {
        if (ba == bb && topo[ba].edges_share_vertex(e, g)) continue;
        const auto& ea = topo[ba].edges;
        const auto& eb = topo[bb].edges;
        test(PairKind::EdgeEdge, {VertexRef{ba, ea[2 * e]}, VertexRef{ba, ea[2 * e + 1]}, VertexRef{bb, eb[2 * g]},
                                  VertexRef{bb, eb[2 * g + 1]}});
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

TriangleMesh falling_cloth() {
  TriangleMesh cloth = make_grid(8, 8, 1.6, 1.6);
  cloth.vertices.col(1).array() += 0.62;
  return cloth;
}

}  // namespace

TEST_CASE("detector finds exactly the all-pairs exact CCD collisions", "[detection][brute-force]") {
  const HierarchyKind hierarchy = GENERATE(HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb);
  const CullingMode culling =
      GENERATE(CullingMode::None, CullingMode::NonPenetration, CullingMode::Projection, CullingMode::Filters,
               CullingMode::Network);
  const double thickness = GENERATE(0.0, 0.01);
  const TriangleMesh cloth = falling_cloth();
  const TriangleMesh obstacle = make_uv_sphere(0.6, 10, 6);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Vertices end = cloth.vertices;
  for (Eigen::Index v = 0; v < end.rows(); ++v) {
    // Falls onto the sphere and crumples a little, so the cloth also hits itself.
    end(v, 1) -= 0.12 + 0.1 * std::cos(3.0 * cloth.vertices(v, 0));
    for (int k = 0; k < 3; ++k) end(v, k) += jitter(rng);
  }
  const std::vector<Frame> frames = {{&cloth.vertices, &end}, {&obstacle.vertices, &obstacle.vertices}};

  DetectorSettings settings;
  settings.hierarchy = hierarchy;
  settings.culling = culling;
  settings.thickness = thickness;
  learning::attach_network_culler(settings, "");
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  CHECK(detector.add_obstacle(obstacle) == 1);
  const std::vector<Collision>& found = detector.detect(cloth.vertices, end);
  std::vector<Key> keys;
  for (const Collision& c : found) {
    keys.push_back(key_of(c));
    CHECK(c.toi >= 0.0);
    CHECK(c.toi <= 1.0);
  }
  std::sort(keys.begin(), keys.end());
  const std::vector<Key> reference = all_pairs_reference(cloth, obstacle, frames, thickness);
  REQUIRE(reference.size() > 0);
  CHECK(keys == reference);
  const DetectionStats& stats = detector.stats();
  CHECK(stats.collisions == static_cast<long>(found.size()));
  CHECK(stats.candidates_vertex_face + stats.candidates_edge_edge >= stats.collisions + stats.culled);
  if (culling == CullingMode::None) CHECK(stats.culled == 0);
}

TEST_CASE("detector output does not depend on the hierarchy or threads", "[detection]") {
  const TriangleMesh cloth = make_grid(16, 16, 1.6, 1.6);
  const TriangleMesh obstacle = make_box(Eigen::Vector3d(0.5, 0.3, 0.5));
  Vertices start = cloth.vertices, end = cloth.vertices;
  start.col(1).array() += 0.35;
  end.col(1).array() += 0.25;
  std::vector<std::vector<Key>> outputs;
  for (HierarchyKind hierarchy : {HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb}) {
    // Serial, parallel under a one-thread limit and parallel with two threads must agree.
    for (const int threads : {0, 1, 2}) {
      DetectorSettings settings;
      settings.hierarchy = hierarchy;
      settings.parallel = threads > 0;
      std::optional<tbb::global_control> limit;
      if (threads == 1) limit.emplace(tbb::global_control::max_allowed_parallelism, 1);
      CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
      detector.add_obstacle(obstacle);
      std::vector<Key> keys;
      for (const Collision& c : detector.detect(start, end)) keys.push_back(key_of(c));
      outputs.push_back(keys);
    }
  }
  REQUIRE_FALSE(outputs[0].empty());  // the cloth sinks into the box top (y = 0.3)
  for (const auto& o : outputs) CHECK(o == outputs[0]);
}

TEST_CASE("detector output and counts do not depend on the block size", "[detection][block]") {
  const CullingMode culling = GENERATE(CullingMode::None, CullingMode::Projection, CullingMode::Filters,
                                       CullingMode::Network);
  const double thickness = GENERATE(0.0, 0.01);
  const auto [cloth, end, obstacle] = test::cloth_over_sphere(0.12);
  std::vector<Collision> reference;
  DetectionStats reference_stats;
  for (const int block_pairs : {1024, 1, 7, 16, 100}) {
    for (const bool parallel : {false, true}) {
      DetectorSettings settings;
      settings.culling = culling;
      settings.thickness = thickness;
      settings.block_pairs = block_pairs;
      settings.parallel = parallel;
      learning::attach_network_culler(settings, "");
      CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
      detector.add_obstacle(obstacle);
      const std::vector<Collision> found = detector.detect(cloth.vertices, end);
      const DetectionStats& stats = detector.stats();
      if (reference.empty()) {
        reference = found;
        reference_stats = stats;
        REQUIRE_FALSE(reference.empty());
        continue;
      }
      test::check_same(found, reference);
      CHECK(stats.candidates_vertex_face == reference_stats.candidates_vertex_face);
      CHECK(stats.candidates_edge_edge == reference_stats.candidates_edge_edge);
      CHECK(stats.culled == reference_stats.culled);
      CHECK(stats.network_dropped == reference_stats.network_dropped);
      CHECK(stats.network_overruled == reference_stats.network_overruled);
      CHECK(stats.network_kept == reference_stats.network_kept);
    }
  }
}

TEST_CASE("a moving obstacle hits a resting cloth, then rests", "[detection][moving]") {
  const TriangleMesh cloth = make_grid(6, 6);
  const TriangleMesh obstacle = make_box(Eigen::Vector3d(0.1, 0.1, 0.1));
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()));
  const int body = detector.add_obstacle(obstacle);
  Eigen::Isometry3d below = Eigen::Isometry3d::Identity(), above = Eigen::Isometry3d::Identity();
  below.translation() = Eigen::Vector3d(0.05, -0.3, 0.03);
  above.translation() = Eigen::Vector3d(0.05, 0.3, 0.03);
  detector.set_obstacle_transforms(body, below, above);
  const auto& hits = detector.detect(cloth.vertices, cloth.vertices);
  REQUIRE_FALSE(hits.empty());
  bool obstacle_involved = false;
  for (const Collision& c : hits) {
    for (const VertexRef& r : c.vertices) obstacle_involved = obstacle_involved || r.body == body;
    // The box top (y = 0.1 above its centre) reaches the cloth (y = 0) at t = (0.3 - 0.1) / 0.6 or later.
    CHECK(c.toi >= 1.0 / 3.0 - 1e-6);
  }
  CHECK(obstacle_involved);
  // Next step: the box rests above the cloth.
  CHECK(detector.detect(cloth.vertices, cloth.vertices).empty());
}

TEST_CASE("detector rejects bad input", "[detection][errors]") {
  const TriangleMesh cloth = make_grid(4, 4);
  const int n = static_cast<int>(cloth.vertex_count());
  DetectorSettings network;
  network.culling = CullingMode::Network;
  CHECK_THROWS_WITH(CollisionDetector(cloth.faces, n, network), Catch::Contains("needs DetectorSettings::culler"));
  DetectorSettings negative;
  negative.thickness = -1.0;
  CHECK_THROWS_AS(CollisionDetector(cloth.faces, n, negative), std::invalid_argument);
  CHECK_THROWS_AS(CollisionDetector(cloth.faces, n - 1), std::invalid_argument);
  CHECK_THROWS_AS(CollisionDetector(Faces(0, 3), n), std::invalid_argument);
  for (const int block_pairs : {0, -5, kMaxBlockPairs + 1}) {
    DetectorSettings bad_block;
    bad_block.block_pairs = block_pairs;
    CHECK_THROWS_WITH(CollisionDetector(cloth.faces, n, bad_block), Catch::Contains("block_pairs"));
  }

  CollisionDetector detector(cloth.faces, n);
  Vertices wrong = cloth.vertices.topRows(n - 1);
  CHECK_THROWS_AS(detector.detect(cloth.vertices, wrong), std::invalid_argument);
  Vertices nan = cloth.vertices;
  nan(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(detector.detect(nan, cloth.vertices), std::invalid_argument);
  CHECK_THROWS_AS(detector.set_obstacle_positions(1, cloth.vertices, cloth.vertices), std::invalid_argument);
  TriangleMesh bad = make_box();
  bad.faces(0, 0) = 100;
  CHECK_THROWS_AS(detector.add_obstacle(bad), std::invalid_argument);
  const int body = detector.add_obstacle(make_box());
  CHECK_THROWS_AS(detector.set_obstacle_positions(body, cloth.vertices, cloth.vertices), std::invalid_argument);
}
