// The searches hand exactly the brute-force pairs to their sink, on one thread and on several (large node pairs
// searched as tasks of their own), in chunks of every size: self and pair searches, unrestricted and restricted to
// moved vertices (both restricted paths), and with a sink that waits for parallel work of its own.
#include <catch2/catch.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "broadphase_scenes.hpp"
#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/collecting_sink.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;
using namespace clothcd::test;

namespace {

// Collects the chunks a search hands over (from any thread) and checks their sizes: none empty, the largest kept.
class CheckedSink final : public CandidateSink {
 public:
  void consume(const CandidateSet& chunk) override {
    if (chunk.size() == 0) empty_chunks.fetch_add(1);
    std::size_t seen = largest.load();
    while (chunk.size() > seen && !largest.compare_exchange_weak(seen, chunk.size())) {
    }
    collecting.consume(chunk);
  }

  CandidateSet found;
  CollectingSink collecting{found};
  std::atomic<std::size_t> largest{0};
  std::atomic<int> empty_chunks{0};
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
    checked.consume(chunk);
  }

  CheckedSink checked;
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

TEST_CASE("streamed searches find exactly the brute-force pairs, serial and parallel", "[broadphase][stream]") {
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
  const bool restricted = moved_share >= 0.0;
  if (restricted) {  // both restricted paths: the primitive queries (few moved) and the restricted descent
    const auto moved_count = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
    CHECK((moved_count * kMovedQueryShare <= moved.size()) == (moved_share < 1.0 / kMovedQueryShare));
  }
  TraversalSettings settings{parallel, restricted ? &moved : nullptr};
  settings.chunk_pairs = chunk;

  CandidateSet self_reference, pair_reference;
  brute_force_self_candidates(cloth_body.view(0), self_reference);
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), pair_reference);
  if (restricted) {
    self_reference = pairs_touching_moved(self_reference, 0, cloth_body.topology, moved);
    pair_reference = pairs_touching_moved(pair_reference, 0, cloth_body.topology, moved);
  }
  REQUIRE(self_reference.size() > 0);
  REQUIRE(pair_reference.size() > 0);

  CheckedSink self_sink;
  TraversalStats stats;
  find_self_candidates(cloth_body.view(0), settings, self_sink, &stats);
  check_same(sorted(self_sink.found), sorted(self_reference));
  CHECK(stats.task_ms > 0.0);

  CheckedSink pair_sink;
  find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), settings, pair_sink);
  check_same(sorted(pair_sink.found), sorted(pair_reference));

  // No chunk is empty, and one holds at most `chunk` pairs plus those of one leaf pair (32-face leaves: well below
  // 8,000 pairs).
  CHECK(self_sink.empty_chunks == 0);
  CHECK(pair_sink.empty_chunks == 0);
  CHECK(std::max(self_sink.largest.load(), pair_sink.largest.load()) < chunk + 8000);

  settings.chunk_pairs = 0;
  CHECK_THROWS_AS(find_self_candidates(cloth_body.view(0), settings, self_sink), std::invalid_argument);
}

TEST_CASE("a streamed search stays exact when its sink waits for parallel work", "[broadphase][stream]") {
  std::mt19937 rng(23);
  const TriangleMesh cloth = folded_sheet(48);
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.03, rng), 0.01, {VolumeKind::Aabb, 32});
  TraversalSettings settings{true, nullptr};
  settings.chunk_pairs = 16;
  CandidateSet reference;
  brute_force_self_candidates(cloth_body.view(0), reference);
  REQUIRE(reference.size() > 1000);
  WaitingSink sink;
  find_self_candidates(cloth_body.view(0), settings, sink);
  CHECK(sink.checked.empty_chunks == 0);
  check_same(sorted(sink.checked.found), sorted(reference));
}
