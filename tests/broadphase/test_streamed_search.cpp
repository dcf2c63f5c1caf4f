// The streamed searches (candidates handed to a sink in chunks, large node pairs searched as tasks of their own) find
// exactly the pairs of the collecting searches, which the brute-force tests check: self and pair searches, serial and
// parallel, of every chunk size, unrestricted and restricted to moved vertices (both restricted paths).
#include <catch2/catch.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <random>
#include <vector>

#include "broadphase_scenes.hpp"
#include "broadphase/candidates.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;
using namespace clothcd::test;

namespace {

// Collects the chunks a search hands over (from any thread) and the largest chunk seen.
class CollectingSink final : public CandidateSink {
 public:
  void consume(const CandidateSet& chunk) override {
    std::lock_guard<std::mutex> lock(mutex_);
    CHECK(chunk.size() > 0);
    largest = std::max(largest, chunk.size());
    found.vertex_face.insert(found.vertex_face.end(), chunk.vertex_face.begin(), chunk.vertex_face.end());
    found.edge_edge.insert(found.edge_edge.end(), chunk.edge_edge.begin(), chunk.edge_edge.end());
  }

  CandidateSet found;
  std::size_t largest = 0;

 private:
  std::mutex mutex_;
};

// A sink that waits for TBB work of its own in every call, as a culler or an observer may: while it waits, its thread
// may take other tasks of the search.
class WaitingSink final : public CandidateSink {
 public:
  void consume(const CandidateSet& chunk) override {
    tbb::parallel_for(0, 16, [](int) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
      while (std::chrono::steady_clock::now() < until) {
      }
    });
    collecting.consume(chunk);
  }

  CollectingSink collecting;
};

CandidateSet sorted(CandidateSet set) {
  sort_candidates(set);
  return set;
}

void check_same(const CandidateSet& found, const CandidateSet& reference) {
  CHECK(found.vertex_face == reference.vertex_face);
  CHECK(found.edge_edge == reference.edge_edge);
}

// A sheet folded over a sphere (large enough that its self search spawns tasks), moved at random.
TriangleMesh folded_sheet(int n) {
  TriangleMesh cloth = make_grid(n, n, 2.4, 2.4);
  for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
    const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2);
    cloth.vertices(v, 1) = 1.02 - 0.5 * (x * x + z * z) + 0.05 * std::sin(9.0 * x);
  }
  return cloth;
}

}  // namespace

TEST_CASE("streamed searches find exactly the collected searches' pairs", "[broadphase][stream]") {
  const bool spheres = GENERATE(false, true);
  const bool parallel = GENERATE(false, true);
  const std::size_t chunk = GENERATE(std::size_t{1}, std::size_t{50}, std::size_t{1024});
  const double moved_share = GENERATE(-1.0, 0.03, 0.3);  // -1: unrestricted
  std::mt19937 rng(17);
  const TriangleMesh cloth = folded_sheet(48);
  const TriangleMesh obstacle = make_uv_sphere(1.0, 24, 12);
  const VolumeKind kind = spheres ? VolumeKind::Sphere : VolumeKind::Aabb;
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.03, rng), 0.01, {kind, 32});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.01, {kind, 32});
  REQUIRE(cloth_body.topology.face_count() > 4096);  // the root's halves are searched as tasks of their own
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(cloth_body.topology.vertex_count));
  std::bernoulli_distribution pick(std::max(moved_share, 0.0));
  for (auto& m : moved) m = pick(rng) ? 1 : 0;
  TraversalSettings settings{parallel, moved_share >= 0.0 ? &moved : nullptr};
  settings.chunk_pairs = chunk;

  CandidateSet self_collected;
  find_self_candidates(cloth_body.view(0), settings, self_collected);
  REQUIRE(self_collected.size() > 0);
  CollectingSink self_sink;
  TraversalStats stats;
  find_self_candidates(cloth_body.view(0), settings, self_sink, &stats);
  check_same(sorted(self_sink.found), sorted(self_collected));
  CHECK(stats.task_ms > 0.0);

  CandidateSet pair_collected;
  find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), settings, pair_collected);
  REQUIRE(pair_collected.size() > 0);
  CollectingSink pair_sink;
  find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), settings, pair_sink);
  check_same(sorted(pair_sink.found), sorted(pair_collected));

  // A chunk holds at most `chunk` pairs plus those of one leaf pair (32-face leaves: well below 8,000 pairs).
  CHECK(std::max(self_sink.largest, pair_sink.largest) < chunk + 8000);

  settings.chunk_pairs = 0;
  CHECK_THROWS_AS(find_self_candidates(cloth_body.view(0), settings, self_sink), std::invalid_argument);
}

TEST_CASE("a streamed search stays exact when its sink waits for parallel work", "[broadphase][stream]") {
  std::mt19937 rng(23);
  const TriangleMesh cloth = folded_sheet(48);
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.03, rng), 0.01, {VolumeKind::Aabb, 32});
  TraversalSettings settings{true, nullptr};
  settings.chunk_pairs = 16;
  CandidateSet collected;
  find_self_candidates(cloth_body.view(0), settings, collected);
  REQUIRE(collected.size() > 1000);
  WaitingSink sink;
  find_self_candidates(cloth_body.view(0), settings, sink);
  check_same(sorted(sink.collecting.found), sorted(collected));
}
