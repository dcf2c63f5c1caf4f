// Reuse within a step (DetectorSettings::reuse_unchanged): repeated detect() calls with the same start positions and a
// few moved end positions must give exactly what a detector without reuse gives (the reference, itself checked
// against all-pairs exact CCD in test_collision_detector.cpp), collision by collision and count by count.
#include <catch2/catch.hpp>

#include <random>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/same_collisions.hpp"

using namespace clothcd;
using clothcd::test::check_same;

namespace {

void check_same_stats(const DetectionStats& a, const DetectionStats& b) {
  CHECK(a.candidates_vertex_face == b.candidates_vertex_face);
  CHECK(a.candidates_edge_edge == b.candidates_edge_edge);
  CHECK(a.culled == b.culled);
  CHECK(a.collisions == b.collisions);
}

// A cloth falling onto a sphere and crumpling (so it also hits itself), moved by `fall` over the step.
Vertices fallen(const TriangleMesh& cloth, double fall, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Vertices end = cloth.vertices;
  for (Eigen::Index v = 0; v < end.rows(); ++v) {
    end(v, 1) -= fall + 0.1 * std::cos(3.0 * cloth.vertices(v, 0));
    for (int k = 0; k < 3; ++k) end(v, k) += jitter(rng);
  }
  return end;
}

}  // namespace

TEST_CASE("repeated detection in a step reuses unmoved pairs and equals a fresh detection", "[detection][reuse]") {
  const HierarchyKind hierarchy = GENERATE(HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb);
  const double thickness = GENERATE(0.0, 0.01);
  const bool parallel = GENERATE(false, true);
  TriangleMesh cloth = make_grid(9, 9, 1.6, 1.6);
  cloth.vertices.col(1).array() += 0.62;
  const TriangleMesh obstacle = make_uv_sphere(0.6, 10, 6);
  std::mt19937 rng(5);

  DetectorSettings settings;
  settings.hierarchy = hierarchy;
  settings.thickness = thickness;
  settings.parallel = parallel;
  DetectorSettings reference_settings = settings;
  reference_settings.reuse_unchanged = false;
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  CollisionDetector reference(cloth.faces, static_cast<int>(cloth.vertex_count()), reference_settings);
  detector.add_obstacle(obstacle);
  reference.add_obstacle(obstacle);

  Vertices start = cloth.vertices;
  Vertices end = fallen(cloth, 0.12, rng);
  std::uniform_int_distribution<Eigen::Index> pick(0, end.rows() - 1);
  std::uniform_real_distribution<double> nudge(-0.02, 0.02);
  long reused = 0, collisions = 0;
  for (int call = 0; call < 6; ++call) {
    if (call == 4) {  // a new step: everything must be searched again
      start = end;
      end = fallen(TriangleMesh{start, cloth.faces}, 0.05, rng);
    } else if (call > 0) {
      // Response-like edits: a few end positions move (one back to its start, i.e. zero motion; one onto another
      // vertex, i.e. coincident vertices); on call 3 nothing moves at all.
      const int count = call == 3 ? 0 : 4;
      for (int i = 0; i < count; ++i) {
        const Eigen::Index v = pick(rng);
        for (int k = 0; k < 3; ++k) end(v, k) += nudge(rng);
      }
      if (call != 3) {
        end.row(pick(rng)) = start.row(pick(rng));
        end.row(pick(rng)) = end.row(pick(rng));
      }
    }
    const std::vector<Collision>& found = detector.detect(start, end);
    const std::vector<Collision>& expected = reference.detect(start, end);
    check_same(found, expected);
    check_same_stats(detector.stats(), reference.stats());
    CHECK(reference.stats().reused == 0);
    if (call == 0 || call == 4) CHECK(detector.stats().reused == 0);
    if (call == 3) CHECK(detector.stats().reused == static_cast<long>(detector.stats().candidates_vertex_face +
                                                                       detector.stats().candidates_edge_edge));
    reused += detector.stats().reused;
    collisions += static_cast<long>(found.size());
  }
  CHECK(reused > 0);
  CHECK(collisions > 0);
}

TEST_CASE("a moved obstacle or the network mode turns reuse off", "[detection][reuse]") {
  TriangleMesh cloth = make_grid(6, 6, 1.0, 1.0);
  const TriangleMesh plate = make_grid(4, 4, 2.0, 2.0);
  Vertices end = cloth.vertices;
  end.col(1).array() -= 0.1;
  cloth.vertices.col(1).array() += 0.05;
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()));
  const int body = detector.add_obstacle(plate);
  detector.detect(cloth.vertices, end);
  Vertices lowered = plate.vertices;
  lowered.col(1).array() -= 0.01;
  detector.set_obstacle_positions(body, plate.vertices, lowered);
  const std::size_t hits = detector.detect(cloth.vertices, end).size();
  CHECK(detector.stats().reused == 0);
  CHECK(hits > 0);
  // The obstacle now rests at `lowered`, which differs from the last call's start: searched in full again.
  detector.detect(cloth.vertices, end);
  CHECK(detector.stats().reused == 0);
  // Unchanged since: reused.
  detector.detect(cloth.vertices, end);
  CHECK(detector.stats().reused > 0);

  DetectorSettings network_settings;
  network_settings.culling = CullingMode::Network;
  learning::attach_network_culler(network_settings, "");
  CollisionDetector network(cloth.faces, static_cast<int>(cloth.vertex_count()), network_settings);
  network.add_obstacle(plate);
  for (int call = 0; call < 2; ++call) {
    network.detect(cloth.vertices, end);
    CHECK(network.stats().reused == 0);
  }
}
