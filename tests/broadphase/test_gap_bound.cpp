// Searches with a gap bound (TraversalSettings::gap_bound): with a fixed bound, exactly the brute-force pairs whose
// boxes are within it (every hierarchy kind, SIMD level, serial and parallel, both kinds of pairs, restricted to moved
// vertices or not); a bound of 0 is the search without one; with a sink that lowers the bound as it goes (branch and
// bound), every pair within the final bound is produced, and the bound prunes. And the seam's tests themselves: the
// box test is the overlap test at 0, the grown boxes and the packed queries pass whatever the box test passes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/collecting_sink.hpp"
#include "broadphase/gap_bound.hpp"
#include "broadphase_scenes.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;
using namespace clothcd::test;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct KindPair {
  VolumeKind cloth;
  VolumeKind obstacle;
};

CandidateSet sorted(CandidateSet set) {
  sort_candidates(set);
  return set;
}

void check_same(const CandidateSet& found, const CandidateSet& reference) {
  CHECK(found.vertex_face.size() == reference.vertex_face.size());
  CHECK(found.edge_edge.size() == reference.edge_edge.size());
  CHECK(found.face_face.size() == reference.face_face.size());
  CHECK(found.vertex_face == reference.vertex_face);
  CHECK(found.edge_edge == reference.edge_edge);
  CHECK(found.face_face == reference.face_face);
}

// The boxes of the bodies that candidates name, by body id.
struct SceneBoxes {
  std::vector<const SweptBoxes*> of_body;

  double gap(const VertexFaceCandidate& c) const {
    return box_gap(of_body[c.vertex_body]->vertices[c.vertex], of_body[c.face_body]->faces[c.face]);
  }
  double gap(const EdgeEdgeCandidate& c) const {
    return box_gap(of_body[c.body_a]->edges[c.edge_a], of_body[c.body_b]->edges[c.edge_b]);
  }
  double gap(const FaceFaceCandidate& c) const {
    return box_gap(of_body[c.body_a]->faces[c.face_a], of_body[c.body_b]->faces[c.face_b]);
  }
  // The smallest box gap of the set's pairs, at least 0 (+infinity for none).
  double smallest(const CandidateSet& set) const {
    double lowest = kInfinity;
    for (const auto& c : set.vertex_face) lowest = std::min(lowest, gap(c));
    for (const auto& c : set.edge_edge) lowest = std::min(lowest, gap(c));
    for (const auto& c : set.face_face) lowest = std::min(lowest, gap(c));
    return std::max(lowest, 0.0);
  }
  // The pairs of `set` whose box gap is at most `bound`.
  CandidateSet within(const CandidateSet& set, double bound) const {
    CandidateSet out;
    for (const auto& c : set.vertex_face) {
      if (gap(c) <= bound) out.vertex_face.push_back(c);
    }
    for (const auto& c : set.edge_edge) {
      if (gap(c) <= bound) out.edge_edge.push_back(c);
    }
    for (const auto& c : set.face_face) {
      if (gap(c) <= bound) out.face_face.push_back(c);
    }
    return out;
  }
};

// Branch and bound: lowers the bound to the smallest box gap (at least 0) of the pairs it is handed, and collects them.
class LoweringSink final : public CandidateSink {
 public:
  LoweringSink(const SceneBoxes& boxes, std::atomic<double>& bound) : boxes_(boxes), bound_(bound) {}

  void consume(const CandidateSet& chunk) override {
    const double lowest = boxes_.smallest(chunk);
    double now = bound_.load();
    while (lowest < now && !bound_.compare_exchange_weak(now, lowest)) {
    }
    collecting_.consume(chunk);
  }

  CandidateSet found;

 private:
  const SceneBoxes& boxes_;
  std::atomic<double>& bound_;
  CollectingSink collecting_{found};
};

// True when every pair of `part` is in `whole` (both sorted).
bool includes(const CandidateSet& whole, const CandidateSet& part) {
  return std::includes(whole.vertex_face.begin(), whole.vertex_face.end(), part.vertex_face.begin(),
                       part.vertex_face.end()) &&
         std::includes(whole.edge_edge.begin(), whole.edge_edge.end(), part.edge_edge.begin(), part.edge_edge.end()) &&
         std::includes(whole.face_face.begin(), whole.face_face.end(), part.face_face.begin(), part.face_face.end());
}

TraversalSettings bounded(bool parallel, SearchedPairs pairs, const std::atomic<double>& bound) {
  TraversalSettings settings;
  settings.parallel = parallel;
  settings.pairs = pairs;
  settings.gap_bound = &bound;
  return settings;
}

}  // namespace

TEST_CASE("a fixed gap bound finds exactly the brute-force pairs within it", "[broadphase][gap]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const SearchedPairs pairs = GENERATE(SearchedPairs::VertexFaceEdgeEdge, SearchedPairs::FaceFace);
  const double gap = GENERATE(0.0, 0.004, 0.03, 0.2, kInfinity);
  const bool parallel = GENERATE(false, true);
  const int leaf = GENERATE(1, 8);
  std::mt19937 rng(5);
  const TriangleMesh cloth = draped_cloth(11);
  TriangleMesh obstacle = make_uv_sphere(1.0, 12, 7);
  obstacle.vertices.col(1).array() -= 0.15;  // apart from the cloth: only a bound brings its pairs
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.03, rng), 0.0, {kinds.cloth, leaf});
  TestBody obstacle_body(obstacle, jitter(obstacle.vertices, 0.01, rng), 0.0, {kinds.obstacle, leaf});

  CandidateSet self_reference, pair_reference;
  brute_force_self_candidates(cloth_body.view(0), self_reference, pairs, gap);
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), pair_reference, pairs, gap);
  REQUIRE(self_reference.size() > 0);
  if (gap >= 0.2) REQUIRE(pair_reference.size() > 0);
  const std::atomic<double> bound{gap};
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet self_found, pair_found;
    find_self_candidates(cloth_body.view(0), bounded(parallel, pairs, bound), self_found);
    check_same(sorted(self_found), sorted(self_reference));
    find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), bounded(parallel, pairs, bound), pair_found);
    check_same(sorted(pair_found), sorted(pair_reference));
  }
}

TEST_CASE("a gap bound of 0 is the search without one", "[broadphase][gap]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const SearchedPairs pairs = GENERATE(SearchedPairs::VertexFaceEdgeEdge, SearchedPairs::FaceFace);
  std::mt19937 rng(8);
  const TriangleMesh cloth = draped_cloth(16);
  const TriangleMesh obstacle = make_uv_sphere(1.0, 14, 8);
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.05, rng), 0.01, {kinds.cloth, 4});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.01, {kinds.obstacle, 4});
  TraversalSettings plain;
  plain.parallel = false;
  plain.pairs = pairs;
  const std::atomic<double> zero{0.0};
  CandidateSet self_plain, self_zero, pair_plain, pair_zero;
  TraversalStats self_plain_stats, self_zero_stats, pair_plain_stats, pair_zero_stats;
  find_self_candidates(cloth_body.view(0), plain, self_plain, &self_plain_stats);
  find_self_candidates(cloth_body.view(0), bounded(false, pairs, zero), self_zero, &self_zero_stats);
  find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), plain, pair_plain, &pair_plain_stats);
  find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), bounded(false, pairs, zero), pair_zero,
                       &pair_zero_stats);
  REQUIRE(self_plain.size() > 0);
  REQUIRE(pair_plain.size() > 0);
  check_same(sorted(self_zero), sorted(self_plain));
  check_same(sorted(pair_zero), sorted(pair_plain));
  // The same tests, only in another order.
  CHECK(self_zero_stats.volume_tests == self_plain_stats.volume_tests);
  CHECK(self_zero_stats.primitive_tests == self_plain_stats.primitive_tests);
  CHECK(pair_zero_stats.volume_tests == pair_plain_stats.volume_tests);
  CHECK(pair_zero_stats.primitive_tests == pair_plain_stats.primitive_tests);
}

TEST_CASE("a negative or NaN gap bound is refused", "[broadphase][gap]") {
  const TriangleMesh cloth = make_grid(6, 6);
  TestBody a(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  TestBody b(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  for (const double wrong : {-1e-300, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    const std::atomic<double> bound{wrong};
    CandidateSet out;
    CHECK_THROWS_AS(find_self_candidates(a.view(0), bounded(false, SearchedPairs::FaceFace, bound), out),
                    std::invalid_argument);
    CHECK_THROWS_AS(
        find_pair_candidates(a.view(0), b.view(1), bounded(false, SearchedPairs::VertexFaceEdgeEdge, bound), out),
        std::invalid_argument);
    CHECK(out.size() == 0);
  }
}

TEST_CASE("a gap bound on searches restricted to moved vertices", "[broadphase][gap][moved]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  // Below 1 / kMovedQueryShare the primitive queries, above it the restricted descent.
  const double moved_share = GENERATE(0.03, 0.3);
  const double gap = GENERATE(0.02, 0.2);
  const bool parallel = GENERATE(false, true);
  std::mt19937 rng(13);
  const TriangleMesh cloth = draped_cloth(12);
  TriangleMesh obstacle = make_uv_sphere(1.0, 12, 7);
  obstacle.vertices.col(1).array() -= 0.1;
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.04, rng), 0.0, {kinds.cloth, 2});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.0, {kinds.obstacle, 2});
  std::bernoulli_distribution pick(moved_share);
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(cloth_body.topology.vertex_count));
  for (auto& m : moved) m = pick(rng) ? 1 : 0;
  const auto moved_count = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  REQUIRE((moved_count * kMovedQueryShare <= moved.size()) == (moved_share < 0.05));

  CandidateSet all, pair_all;
  brute_force_self_candidates(cloth_body.view(0), all, SearchedPairs::VertexFaceEdgeEdge, gap);
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), pair_all, SearchedPairs::VertexFaceEdgeEdge,
                              gap);
  const CandidateSet self_reference = pairs_touching_moved(all, 0, cloth_body.topology, moved);
  const CandidateSet pair_reference = pairs_touching_moved(pair_all, 0, cloth_body.topology, moved);
  REQUIRE(self_reference.size() > 0);
  if (gap >= 0.2) REQUIRE(pair_reference.size() > 0);
  const std::atomic<double> bound{gap};
  TraversalSettings settings = bounded(parallel, SearchedPairs::VertexFaceEdgeEdge, bound);
  settings.moved_vertices = &moved;
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet found, pair_found;
    find_self_candidates(cloth_body.view(0), settings, found);
    check_same(sorted(found), sorted(self_reference));
    find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), settings, pair_found);
    check_same(sorted(pair_found), sorted(pair_reference));
  }
}

TEST_CASE("a bound lowered by the sink prunes nothing within its final value", "[broadphase][gap][branch-and-bound]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const SearchedPairs pairs = GENERATE(SearchedPairs::VertexFaceEdgeEdge, SearchedPairs::FaceFace);
  const bool parallel = GENERATE(false, true);
  const std::size_t chunk = GENERATE(std::size_t{1}, std::size_t{64});
  std::mt19937 rng(21);
  // Separate small triangles (every self pair of positive gap), and a cloth held above a sphere.
  const TriangleMesh soup = scattered_triangles(400, 0.01, rng);
  const TriangleMesh cloth = draped_cloth(14);
  TriangleMesh obstacle = make_uv_sphere(1.0, 16, 9);
  obstacle.vertices.col(1).array() -= 0.08;
  const TestBody soup_body(soup, soup.vertices, 0.0, {kinds.cloth, 4});
  const TestBody cloth_body(cloth, jitter(cloth.vertices, 0.01, rng), 0.0, {kinds.cloth, 4});
  const TestBody obstacle_body(obstacle, obstacle.vertices, 0.0, {kinds.obstacle, 4});

  auto check = [&](const SceneBoxes& boxes, const CandidateSet& all, const auto& search) {
    const double smallest = boxes.smallest(all);
    for (const SimdLevel level : cpu_simd_levels()) {
      INFO("level " << simd_level_name(level));
      test::SimdLimit capped(level);
      std::atomic<double> bound{kInfinity};
      LoweringSink sink(boxes, bound);
      TraversalSettings settings = bounded(parallel, pairs, bound);
      settings.chunk_pairs = chunk;
      search(settings, sink);
      // The bound ends at the smallest gap of all pairs, and every pair that close was produced.
      CHECK(bound.load() == smallest);
      const CandidateSet found = sorted(sink.found);
      CHECK(includes(found, sorted(boxes.within(all, bound.load()))));
      CHECK(includes(sorted(all), found));
      // And the bound pruned: far fewer pairs than the unbounded search's.
      CHECK(found.size() * 20 < all.size());
    }
  };
  CandidateSet self_all;
  brute_force_self_candidates(soup_body.view(0), self_all, pairs, kInfinity);
  check(SceneBoxes{{&soup_body.boxes}}, self_all, [&](const TraversalSettings& settings, CandidateSink& sink) {
    find_self_candidates(soup_body.view(0), settings, sink);
  });
  CandidateSet pair_all;
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), pair_all, pairs, kInfinity);
  check(SceneBoxes{{&cloth_body.boxes, &obstacle_body.boxes}}, pair_all,
        [&](const TraversalSettings& settings, CandidateSink& sink) {
          find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), settings, sink);
        });
}

TEST_CASE("the gap seam: the box test, the grown boxes and the packed queries agree", "[broadphase][gap]") {
  // Boxes whose bounds are a gap apart, or a rounding step more or less, at magnitudes from subnormal to huge.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> exponent(-1060, 1000);
  std::uniform_int_distribution<int> steps(-2, 2);
  int passed = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const double scale = std::ldexp(1.0, exponent(rng));
    const double gap = trial % 7 == 0 ? 0.0 : unit(rng) * scale;
    FlatBox a, b;
    for (int k = 0; k < 3; ++k) {
      a.min[k] = (unit(rng) - 0.5) * scale;
      a.max[k] = a.min[k] + unit(rng) * scale;
      // b lies above a along this axis, about `gap` away, moved by a few units in the last place.
      double lo = a.max[k] + gap;
      for (int s = steps(rng); s != 0; s += s > 0 ? -1 : 1) lo = std::nextafter(lo, s > 0 ? kInfinity : -kInfinity);
      b.min[k] = lo;
      b.max[k] = lo + unit(rng) * scale;
    }
    const bool near = detail::within(a, b, gap);
    CHECK(near == detail::within(b, a, gap));
    CHECK(detail::within(a, b, 0.0) == a.overlaps(b));
    CHECK(detail::within(a, b, kInfinity));
    if (!near) continue;
    ++passed;
    CHECK(detail::reach_box(a, gap).overlaps(b));
    CHECK(detail::reach_box(b, gap).overlaps(a));
    const PackedBox q = detail::packed_reach(a, pack_box(a), gap);
    const PackedBox p = pack_box(b);
    bool packed_overlap = true;
    for (int k = 0; k < 3; ++k) packed_overlap = packed_overlap && q.lo[k] <= p.hi[k] && p.lo[k] <= q.hi[k];
    CHECK(packed_overlap);
  }
  CHECK(passed > 10000);
}
