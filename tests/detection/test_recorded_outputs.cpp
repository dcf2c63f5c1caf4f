// Outputs recorded at commit 8747123, on the baseline instruction set, before the library's code was moved into its
// present files and its settings into one plan: the collision digests of detect() and earliest_impact() over the
// hierarchies, culling modes, thicknesses and thread counts, the simulation's state hashes, and the committed pair
// network's probabilities. Code that only moves must leave every one of them the same, bit for bit. The baseline
// level makes them the same on every x86-64 CPU (a wide path may add a sum in another order).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/culling/pair_classifier.hpp"
#include "clothcd/culling/pair_features.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/simulation/scene.hpp"
#include "clothcd/simulation/simulator.hpp"
#include "detection/cloth_over_sphere.hpp"
#include "support/simd_limit.hpp"

namespace {

using namespace clothcd;
using simulation::make_scene;
using simulation::Scene;
using simulation::SceneSettings;
using simulation::SimulationSettings;
using simulation::Simulator;

// FNV-1a over bytes: the digest of a run's output.
class Digest {
 public:
  template <class T>
  void add(const T& value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (const unsigned char b : bytes) hash_ = (hash_ ^ b) * 0x100000001b3ULL;
  }
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

void add_collision(Digest& digest, const Collision& c) {
  digest.add(static_cast<int>(c.kind));
  for (const VertexRef& v : c.vertices) {
    digest.add(v.body);
    digest.add(v.vertex);
  }
  digest.add(c.toi);
  for (int k = 0; k < 3; ++k) digest.add(c.normal[k]);
  for (const double p : c.parameters) digest.add(p);
  digest.add(c.conservative);
}

// The digest of one detect() call's collisions and counts, and of earliest_impact() on the same step.
std::uint64_t detection_digest(const Faces& faces, const Vertices& start, const Vertices& end,
                               const TriangleMesh* obstacle, const DetectorSettings& settings) {
  CollisionDetector detector(faces, static_cast<int>(start.rows()), settings);
  if (obstacle != nullptr) detector.add_obstacle(*obstacle);
  Digest digest;
  for (const Collision& c : detector.detect(start, end)) add_collision(digest, c);
  const DetectionStats& stats = detector.stats();
  digest.add(stats.candidates_vertex_face);
  digest.add(stats.candidates_edge_edge);
  digest.add(stats.culled);
  const EarliestImpact earliest = detector.earliest_impact(start, end);
  digest.add(earliest.toi);
  digest.add(earliest.windows);
  if (earliest.hit) add_collision(digest, earliest.pair);
  return digest.value();
}

const char* hierarchy_name(HierarchyKind kind) {
  switch (kind) {
    case HierarchyKind::SphereRootAabb: return "sphere-root-aabb";
    case HierarchyKind::Aabb: return "aabb";
    case HierarchyKind::AabbObb: return "aabb-obb";
  }
  return "?";
}

const char* culling_name(CullingMode mode) {
  switch (mode) {
    case CullingMode::None: return "none";
    case CullingMode::NonPenetration: return "nonpenetration";
    case CullingMode::Projection: return "projection";
    case CullingMode::Filters: return "filters";
    case CullingMode::Network: return "network";
  }
  return "?";
}

// A 16 x 16 cloth crumpling into itself over one step: folded like an accordion along x, its layers at nearly the
// same height (a wave and a seeded jitter), so that they pass through each other.
struct CrumpleStep {
  TriangleMesh cloth;
  Vertices end;
};

CrumpleStep crumple_step() {
  constexpr double kPi = 3.14159265358979323846;
  CrumpleStep step;
  step.cloth = make_grid(16, 16, 1.0, 1.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  step.end = step.cloth.vertices;
  for (Eigen::Index v = 0; v < step.end.rows(); ++v) {
    const double x = step.cloth.vertices(v, 0), z = step.cloth.vertices(v, 2);
    step.end(v, 0) = 0.3 * std::sin(3.0 * kPi * x);
    step.end(v, 1) += 0.02 * std::sin(7.0 * z);
    for (int k = 0; k < 3; ++k) step.end(v, k) += jitter(rng);
  }
  return step;
}

// Every recorded detection run, by name: a cloth falling onto a sphere, and a cloth crumpling into itself.
std::map<std::string, std::uint64_t> detection_digests() {
  const auto network = learning::load_network_culler();
  std::map<std::string, std::uint64_t> digests;
  const test::ClothOverSphere sphere_step = test::cloth_over_sphere(0.14);
  const CrumpleStep crumple = crumple_step();
  for (const HierarchyKind hierarchy : {HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb}) {
    for (const CullingMode culling : {CullingMode::None, CullingMode::NonPenetration, CullingMode::Projection,
                                      CullingMode::Filters, CullingMode::Network}) {
      for (const double thickness : {0.0, 1e-3}) {
        for (const bool parallel : {false, true}) {
          DetectorSettings settings;
          settings.hierarchy = hierarchy;
          settings.culling = culling;
          settings.culler = network;
          settings.thickness = thickness;
          settings.parallel = parallel;
          const std::string name = std::string(hierarchy_name(hierarchy)) + " " + culling_name(culling) + " h=" +
                                   (thickness > 0 ? "1e-3" : "0") + (parallel ? " parallel" : " serial");
          digests["sphere " + name] = detection_digest(sphere_step.cloth.faces, sphere_step.cloth.vertices,
                                                       sphere_step.end, &sphere_step.obstacle, settings);
          if (hierarchy != HierarchyKind::AabbObb) {
            digests["crumple " + name] =
                detection_digest(crumple.cloth.faces, crumple.cloth.vertices, crumple.end, nullptr, settings);
          }
        }
      }
    }
  }
  return digests;
}

// The state hash after `steps` steps of the box scene with a 12 x 12 cloth, in each culling mode.
std::map<std::string, std::uint64_t> simulation_hashes(int steps) {
  SceneSettings scene_settings;
  scene_settings.name = "box";
  scene_settings.resolution = 12;
  const Scene scene = make_scene(scene_settings);
  std::map<std::string, std::uint64_t> hashes;
  for (const CullingMode culling : {CullingMode::Filters, CullingMode::Network}) {
    SimulationSettings settings;
    settings.detector.culling = culling;
    if (culling == CullingMode::Network) settings.detector.culler = learning::load_network_culler();
    Simulator simulator(scene, settings);
    for (int s = 0; s < steps; ++s) simulator.step();
    hashes[std::string("box ") + culling_name(culling)] = simulator.state_hash();
  }
  return hashes;
}

// The digest of the committed network's probabilities on seeded random pairs of both kinds.
std::uint64_t network_probability_digest() {
  const learning::PairClassifier classifier = learning::PairClassifier::load(learning::default_network_model_dir());
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Digest digest;
  for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
    std::vector<ccd::CcdQuery> pairs(500);
    for (ccd::CcdQuery& pair : pairs) {
      pair.kind = kind;
      for (int k = 0; k < 4; ++k) {
        for (int c = 0; c < 3; ++c) {
          pair.start[k][c] = coordinate(rng);
          pair.end[k][c] = pair.start[k][c] + 0.1 * coordinate(rng);
        }
      }
    }
    learning::PairFeatureBatch batch;
    learning::compute_pair_features(pairs.data(), pairs.size(), learning::FeatureSettings{}, batch);
    std::vector<double> probabilities(pairs.size());
    classifier.probabilities(batch, probabilities.data());
    for (const double p : probabilities) digest.add(p);
  }
  return digest.value();
}

}  // namespace

TEST_CASE("detection, simulation and the network give the outputs recorded before the redesign", "[recorded]") {
  const test::SimdLimit baseline(SimdLevel::Baseline);
  const std::map<std::string, std::uint64_t> recorded_detection = {
#include "detection/recorded_detection_digests.inc"
  };
  const std::map<std::string, std::uint64_t> detection = detection_digests();
  REQUIRE(detection.size() == recorded_detection.size());
  for (const auto& [name, digest] : detection) {
    INFO(name);
    CHECK(digest == recorded_detection.at(name));
  }
  const std::map<std::string, std::uint64_t> simulation = simulation_hashes(120);
  CHECK(simulation.at("box filters") == 0xaf328b1ca6b7fa65ULL);
  CHECK(simulation.at("box network") == 0xaf328b1ca6b7fa65ULL);
  CHECK(network_probability_digest() == 0xbb485edf5ae547b8ULL);
}
