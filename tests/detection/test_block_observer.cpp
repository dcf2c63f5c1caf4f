// The detector's block observer: it sees every candidate pair of a detect() call exactly once (the count of
// DetectionStats), with culling and exact-test outcomes that agree with the stats and the collisions returned, in
// every culling mode, serially and on threads, whatever the block size; a re-test call shows only the pairs it
// searches again.
#include <catch2/catch.hpp>

#include <algorithm>
#include <mutex>
#include <set>
#include <tuple>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/cloth_over_sphere.hpp"

using namespace clothcd;

namespace {

using PairId = std::tuple<int, std::uint64_t>;                              // kind, order key
using Vertices4 = std::tuple<int, int, int, int, int, int, int, int, int>;  // kind, then (body, vertex) x 4

Vertices4 vertices_of(PairKind kind, const std::array<VertexRef, 4>& v) {
  return {static_cast<int>(kind), v[0].body, v[0].vertex, v[1].body, v[1].vertex,
          v[2].body,              v[2].vertex, v[3].body, v[3].vertex};
}

// What an observer saw in one detect() call.
struct Seen {
  std::mutex mutex;
  std::multiset<PairId> pairs;
  std::vector<std::pair<PairId, Vertices4>> colliding;
  long culled = 0;

  void add(const ObservedBlock& b) {
    std::lock_guard<std::mutex> lock(mutex);
    const ccd::PairBlock& block = *b.pairs;
    for (int i = 0; i < block.size(); ++i) {
      CHECK(block.tag(i) == static_cast<std::uint64_t>(i));
      const PairId id{static_cast<int>(block.kind()), b.keys[i]};
      pairs.insert(id);
      culled += b.culled[i];
      if (b.colliding[i]) {
        CHECK(b.culled[i] == 0);
        colliding.emplace_back(id, vertices_of(block.kind(), block.vertices(i)));
      }
    }
  }
};

}  // namespace

TEST_CASE("the block observer sees every candidate pair once, with its culling and exact outcome",
          "[detection][observer]") {
  const CullingMode culling = GENERATE(CullingMode::None, CullingMode::Filters, CullingMode::Network);
  const bool parallel = GENERATE(false, true);
  const int block_pairs = GENERATE(7, 1024);
  const double thickness = GENERATE(0.0, 0.01);
  const auto [cloth, end, obstacle] = test::cloth_over_sphere(0.15);

  DetectorSettings settings;
  settings.culling = culling;
  settings.parallel = parallel;
  settings.block_pairs = block_pairs;
  settings.thickness = thickness;
  learning::attach_network_culler(settings, "");
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  detector.add_obstacle(obstacle);
  Seen seen;
  detector.set_block_observer([&seen](const ObservedBlock& b) { seen.add(b); });
  const std::vector<Collision>& found = detector.detect(cloth.vertices, end);
  const DetectionStats& stats = detector.stats();

  REQUIRE(stats.collisions > 0);
  CHECK(static_cast<long>(seen.pairs.size()) == stats.candidates_vertex_face + stats.candidates_edge_edge);
  CHECK(std::set<PairId>(seen.pairs.begin(), seen.pairs.end()).size() == seen.pairs.size());  // each pair once
  CHECK(seen.culled == stats.culled);
  // The colliding pairs are the collisions returned; sorted by kind and order key, in the same order.
  REQUIRE(seen.colliding.size() == found.size());
  std::sort(seen.colliding.begin(), seen.colliding.end());
  for (std::size_t i = 0; i < found.size(); ++i) {
    CHECK(seen.colliding[i].second == vertices_of(found[i].kind, found[i].vertices));
  }

  // A re-test call with a few moved vertices shows just the pairs it searches again.
  if (culling != CullingMode::Network) {
    Vertices moved = end;
    moved.row(5) += Eigen::RowVector3d(0.0, -0.05, 0.0);
    Seen again;
    detector.set_block_observer([&again](const ObservedBlock& b) { again.add(b); });
    detector.detect(cloth.vertices, moved);
    const DetectionStats& retest = detector.stats();
    REQUIRE(retest.reused > 0);
    CHECK(static_cast<long>(again.pairs.size()) ==
          retest.candidates_vertex_face + retest.candidates_edge_edge - retest.reused);
  }

  // An empty observer stops the observation.
  detector.set_block_observer({});
  const long before = static_cast<long>(seen.pairs.size());
  detector.detect(cloth.vertices, end);
  CHECK(static_cast<long>(seen.pairs.size()) == before);
}
