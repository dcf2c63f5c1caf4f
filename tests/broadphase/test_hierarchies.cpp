// Every hierarchy returns exactly the brute-force pairs whose swept boxes overlap: cloth self-collision and cloth vs
// obstacle, on seeded random motions of a cloth over a sphere and a box, and on random triangle soups.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "broadphase_scenes.hpp"
#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/collecting_sink.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

using namespace clothcd;
using namespace clothcd::broadphase;
using namespace clothcd::test;

namespace {

struct KindPair {
  VolumeKind cloth;
  VolumeKind obstacle;
};

CandidateSet sorted(CandidateSet set) {
  sort_candidates(set);
  return set;
}

bool has_duplicates(const CandidateSet& set) {
  return std::adjacent_find(set.vertex_face.begin(), set.vertex_face.end()) != set.vertex_face.end() ||
         std::adjacent_find(set.edge_edge.begin(), set.edge_edge.end()) != set.edge_edge.end();
}

void check_same(const CandidateSet& found, const CandidateSet& reference) {
  CHECK(found.vertex_face.size() == reference.vertex_face.size());
  CHECK(found.edge_edge.size() == reference.edge_edge.size());
  CHECK(found.vertex_face == reference.vertex_face);
  CHECK(found.edge_edge == reference.edge_edge);
}

}  // namespace

TEST_CASE("hierarchies match brute force on a cloth draped over obstacles", "[broadphase][brute-force]") {
  const auto kinds = GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
                              KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const int leaf = GENERATE(1, 3, 16, 32);  // 16, 32 (the default): leaves span several groups of the packed tests
  const bool parallel = GENERATE(false, true);
  const int seed = GENERATE(1, 2, 3);
  const bool sphere_obstacle = seed != 2;
  std::mt19937 rng(seed);
  const TriangleMesh cloth = draped_cloth(13);
  const TriangleMesh obstacle = sphere_obstacle ? make_uv_sphere(1.0, 14, 8) : make_box(Eigen::Vector3d(0.8, 0.9, 0.7));
  const double thickness = 0.01 * seed;
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.08, rng), thickness, {kinds.cloth, leaf});
  TestBody obstacle_body(obstacle, jitter(obstacle.vertices, 0.02, rng), thickness, {kinds.obstacle, leaf});

  CandidateSet reference;
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), reference);
  REQUIRE(reference.size() > 0);  // the scene must exercise the search
  // Self-collision uses the cloth side's volume (AABB or sphere).
  CandidateSet self_reference;
  brute_force_self_candidates(cloth_body.view(0), self_reference);
  REQUIRE(self_reference.size() > 0);
  // Every SIMD level the CPU runs (four-lane leaf tests on the baseline, eight from AVX2 up).
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet found;
    TraversalStats stats;
    find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), {parallel}, found, &stats);
    CHECK_FALSE(has_duplicates(sorted(found)));
    check_same(sorted(found), sorted(reference));
    CandidateSet self_found;
    find_self_candidates(cloth_body.view(0), {parallel}, self_found);
    CHECK_FALSE(has_duplicates(sorted(self_found)));
    check_same(sorted(self_found), sorted(self_reference));
  }
}

TEST_CASE("hierarchies match brute force after refits and rebuilds", "[broadphase][brute-force][refit]") {
  const auto kinds = GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
                              KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  std::mt19937 rng(7);
  const TriangleMesh cloth = draped_cloth(11);
  const TriangleMesh obstacle = make_uv_sphere(1.0, 12, 7);
  TestBody cloth_body(cloth, cloth.vertices, 0.0, {kinds.cloth, 2, 1.5});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.0, {kinds.obstacle, 2, 1.5});
  Vertices cloth_now = cloth.vertices;
  Vertices obstacle_now = obstacle.vertices;
  for (int step = 0; step < 6; ++step) {
    const Vertices cloth_next = jitter(cloth_now, 0.05 * (step + 1), rng);
    Vertices obstacle_next = obstacle_now;
    obstacle_next.col(0).array() += 0.03;  // the obstacle slides along x
    compute_swept_boxes(cloth_body.topology, cloth_now, cloth_next, 0.0, cloth_body.boxes);
    compute_swept_boxes(obstacle_body.topology, obstacle_now, obstacle_next, 0.0, obstacle_body.boxes);
    cloth_body.bvh.update(cloth_body.topology, cloth_body.boxes, cloth_now, cloth_next);
    obstacle_body.bvh.update(obstacle_body.topology, obstacle_body.boxes, obstacle_now, obstacle_next);

    CandidateSet reference, found;
    brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), reference);
    find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), {true}, found);
    check_same(sorted(found), sorted(reference));
    CandidateSet self_reference, self_found;
    brute_force_self_candidates(cloth_body.view(0), self_reference);
    find_self_candidates(cloth_body.view(0), {true}, self_found);
    check_same(sorted(self_found), sorted(self_reference));
    cloth_now = cloth_next;
    obstacle_now = obstacle_next;
  }
  // The motion grows every box far beyond its built size, so the rule (ratio 1.5) must have fired.
  CHECK(cloth_body.bvh.build_count() > 1);
}

TEST_CASE("hierarchies match brute force on random triangle soups", "[broadphase][brute-force][random]") {
  const auto kinds = GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
                              KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const int seed = GENERATE(range(10, 16));
  // Far from the origin, the single-precision pre-selection is far coarser than the features: the result must not
  // change (only the double-precision boxes decide).
  const double offset = GENERATE(0.0, 3.0e7);
  std::mt19937 rng(seed);
  TriangleMesh a = random_soup(60, 90, rng);
  TriangleMesh b = random_soup(50, 70, rng);
  b.vertices.array() += 0.3;
  a.vertices.array() += offset;
  b.vertices.array() += offset;
  TestBody body_a(a, jitter(a.vertices, 0.05, rng), 0.0, {kinds.cloth, 1 + seed % 3});
  TestBody body_b(b, jitter(b.vertices, 0.05, rng), 0.001, {kinds.obstacle, 1 + seed % 4});

  CandidateSet reference, self_reference;
  brute_force_pair_candidates(body_a.view(0), body_b.view(3), reference);
  brute_force_self_candidates(body_a.view(0), self_reference);
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet found, self_found;
    find_pair_candidates(body_a.view(0), body_b.view(3), {seed % 2 == 0}, found);
    check_same(sorted(found), sorted(reference));
    find_self_candidates(body_a.view(0), {seed % 2 == 1}, self_found);
    check_same(sorted(self_found), sorted(self_reference));
  }
}

TEST_CASE("self-collision never pairs primitives that share a vertex", "[broadphase][self]") {
  // A flat, still grid: every vertex box touches its neighbours' boxes, so only topology can remove adjacent pairs.
  const TriangleMesh cloth = make_grid(20, 20);
  TestBody body(cloth, cloth.vertices, 1e-3, {VolumeKind::Aabb, 2});
  CandidateSet found;
  find_self_candidates(body.view(0), {true}, found);
  for (const auto& c : found.vertex_face) CHECK_FALSE(body.topology.face_has_vertex(c.face, c.vertex));
  for (const auto& c : found.edge_edge) CHECK_FALSE(body.topology.edges_share_vertex(c.edge_a, c.edge_b));
  // Flat boxes touch along cell borders: a degenerate case for the box tests; still exactly the brute force.
  CandidateSet reference;
  brute_force_self_candidates(body.view(0), reference);
  check_same(sorted(found), sorted(reference));
  // A naive triangle-pair query would return every adjacent pair; ours returns far fewer pairs than that.
  CHECK(found.size() < static_cast<std::size_t>(body.topology.face_count()) * 6);
}

TEST_CASE("the root double box tests the sphere first and the AABB only after it", "[broadphase][double-box]") {
  // Two thin triangles along the (1, 1, 0) diagonal, the second moved by (1.1, 0.3): the boxes [0, 1]^2 and
  // [1.1, 2.1] x [0.3, 1.3] are disjoint, but the circumspheres (radius ~0.71, centres 1.14 apart) overlap.
  auto rod = [](double offset) {
    TriangleMesh m;
    m.vertices.resize(3, 3);
    m.vertices << 0, 0, 0, 1, 1, 0, 1.0, 0.999, 0;
    m.vertices.col(0).array() += offset;
    m.vertices.col(1).array() += 0.3 * offset / 1.1;
    m.faces.resize(1, 3);
    m.faces << 0, 1, 2;
    return m;
  };
  const TriangleMesh a = rod(0.0), b = rod(1.1);
  const BvhSettings spheres{VolumeKind::Sphere, 1};
  TestBody body_a(a, a.vertices, 0.0, spheres), body_b(b, b.vertices, 0.0, spheres);
  CandidateSet found;
  TraversalStats stats;
  find_pair_candidates(body_a.view(0), body_b.view(1), {false}, found, &stats);
  CHECK(stats.root_sphere_overlap);
  CHECK_FALSE(stats.root_aabb_overlap);
  CHECK(found.size() == 0);

  // Far apart: the sphere test alone rejects.
  TriangleMesh far = rod(0.0);
  far.vertices.array() += 10.0;
  TestBody body_far(far, far.vertices, 0.0, spheres);
  TraversalStats far_stats;
  find_pair_candidates(body_a.view(0), body_far.view(1), {false}, found, &far_stats);
  CHECK_FALSE(far_stats.root_sphere_overlap);
  CHECK(far_stats.volume_tests == 1);
}

TEST_CASE("rebuild rule: ratio 0 rebuilds every step, infinity never", "[broadphase][refit]") {
  const TriangleMesh cloth = make_grid(8, 8);
  std::mt19937 rng(3);
  TestBody always(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2, 0.0});
  TestBody never(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2, std::numeric_limits<double>::infinity()});
  for (int step = 0; step < 3; ++step) {
    const Vertices next = jitter(cloth.vertices, 0.5, rng);
    compute_swept_boxes(always.topology, cloth.vertices, next, 0.0, always.boxes);
    CHECK(always.bvh.update(always.topology, always.boxes, cloth.vertices, next) == BvhUpdate::Rebuilt);
    CHECK(never.bvh.update(always.topology, always.boxes, cloth.vertices, next) == BvhUpdate::Refitted);
  }
  CHECK(always.bvh.build_count() == 4);
  CHECK(never.bvh.build_count() == 1);
}

TEST_CASE("unsupported hierarchy pairs are rejected", "[broadphase]") {
  const TriangleMesh cloth = make_grid(4, 4);
  TestBody a(cloth, cloth.vertices, 0.0, {VolumeKind::Obb, 2});
  TestBody b(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  CandidateSet out;
  CHECK_THROWS_AS(find_pair_candidates(a.view(0), b.view(1), {}, out), std::invalid_argument);
  CHECK_THROWS_AS(find_self_candidates(a.view(0), {}, out), std::invalid_argument);
}

TEST_CASE("searches restricted to moved vertices return exactly the brute-force pairs touching them",
          "[broadphase][brute-force][moved]") {
  const auto kinds = GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb},
                              KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
                              KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  // Shares below 1 / kMovedQueryShare take the primitive queries, the others the restricted descent.
  const double moved_share = GENERATE(0.0, 0.02, 0.04, 0.3, 1.0);
  const bool parallel = GENERATE(false, true);
  std::mt19937 rng(11);
  const TriangleMesh cloth = draped_cloth(12);
  const TriangleMesh obstacle = make_uv_sphere(1.0, 12, 7);
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.06, rng), 0.01, {kinds.cloth, 2});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.01, {kinds.obstacle, 2});
  std::bernoulli_distribution pick(moved_share);
  std::vector<std::uint8_t> moved(cloth_body.topology.vertex_count);
  for (auto& m : moved) m = pick(rng) ? 1 : 0;
  const auto moved_count = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  INFO("moved " << moved_count << " of " << moved.size());
  if (moved_share > 0.0 && moved_share < 0.05) REQUIRE(moved_count * kMovedQueryShare <= moved.size());
  if (moved_share >= 0.3) REQUIRE(moved_count * kMovedQueryShare > moved.size());
  const TraversalSettings restricted{parallel, &moved};

  CandidateSet all, pair_all;
  brute_force_self_candidates(cloth_body.view(0), all);
  brute_force_pair_candidates(cloth_body.view(0), obstacle_body.view(1), pair_all);
  const CandidateSet self_reference = pairs_touching_moved(all, 0, cloth_body.topology, moved);
  const CandidateSet pair_reference = pairs_touching_moved(pair_all, 0, cloth_body.topology, moved);
  if (moved_share > 0.0) REQUIRE(self_reference.size() > 0);
  if (moved_share > 0.0) REQUIRE(pair_reference.size() > 0);
  // Every SIMD level the CPU runs (four-lane leaf and primitive tests on the baseline, eight from AVX2 up).
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet found;
    find_self_candidates(cloth_body.view(0), restricted, found);
    CHECK_FALSE(has_duplicates(sorted(found)));
    check_same(sorted(found), sorted(self_reference));
    CandidateSet pair_found;
    find_pair_candidates(cloth_body.view(0), obstacle_body.view(1), restricted, pair_found);
    check_same(sorted(pair_found), sorted(pair_reference));
  }

  std::vector<std::uint8_t> wrong_size(3, 1);
  CandidateSet out;
  CHECK_THROWS_AS(find_self_candidates(cloth_body.view(0), {parallel, &wrong_size}, out), std::invalid_argument);
}

TEST_CASE("a hierarchy needs only the vertex boxes and refuses a wrong count", "[broadphase][refit]") {
  // The hierarchy derives edge and face boxes from the vertex boxes: fed vertex boxes only, it holds exactly the boxes
  // it holds when fed all of them, over a build and two refits of seeded random motion.
  const TriangleMesh cloth = draped_cloth(9);
  std::mt19937 rng(29);
  for (const VolumeKind kind : {VolumeKind::Aabb, VolumeKind::Sphere, VolumeKind::Obb}) {
    Bvh full({kind, 4, 2.0}), lean({kind, 4, 2.0});
    SweptBoxes all, vertices_only;
    for (int step = 0; step < 3; ++step) {
      const Vertices end = jitter(cloth.vertices, 0.05, rng);
      const BodyTopology topology = build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count()));
      compute_swept_boxes(topology, cloth.vertices, end, 0.01, all);
      compute_swept_vertex_boxes(cloth.vertices, end, 0.01, vertices_only);
      CHECK(vertices_only.edges.empty());
      CHECK(vertices_only.faces.empty());
      REQUIRE(vertices_only.vertices.size() == all.vertices.size());
      CHECK(std::equal(all.vertices.begin(), all.vertices.end(), vertices_only.vertices.begin(),
                       [](const FlatBox& a, const FlatBox& b) { return std::memcmp(&a, &b, sizeof a) == 0; }));
      (void)full.update(topology, all, cloth.vertices, end);
      (void)lean.update(topology, vertices_only, cloth.vertices, end);
      auto same = [](const std::vector<FlatBox>& a, const std::vector<FlatBox>& b) {
        // memcmp is not to be given the null data() of an empty vector, even for zero bytes
        return a.size() == b.size() &&
               (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(FlatBox)) == 0);
      };
      CHECK(same(full.ordered_face_boxes(), lean.ordered_face_boxes()));
      CHECK(same(full.ordered_edge_boxes(), lean.ordered_edge_boxes()));
      CHECK(same(full.ordered_vertex_boxes(), lean.ordered_vertex_boxes()));
      CHECK(same(full.boxes(), lean.boxes()));
      // And the edge and face boxes are the ones compute_swept_boxes makes, in tree order.
      for (std::size_t p = 0; p < lean.face_order().size(); ++p) {
        CHECK(std::memcmp(&lean.ordered_face_boxes()[p], &all.faces[lean.face_order()[p]], sizeof(FlatBox)) == 0);
      }
      for (std::size_t i = 0; i < lean.owned_edges().size(); ++i) {
        CHECK(std::memcmp(&lean.ordered_edge_boxes()[i], &all.edges[lean.owned_edges()[i]], sizeof(FlatBox)) == 0);
      }
    }
    SweptBoxes short_by_one = vertices_only;
    short_by_one.vertices.pop_back();
    const BodyTopology topology = build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count()));
    CHECK_THROWS_AS(lean.update(topology, short_by_one, cloth.vertices, cloth.vertices), std::invalid_argument);
    CHECK_THROWS_AS(Bvh({kind, 4, 2.0}).build(topology, short_by_one, cloth.vertices, cloth.vertices),
                    std::invalid_argument);
  }
}

TEST_CASE("a hierarchy refuses non-finite boxes and splits coincident or far-flung triangles", "[broadphase]") {
  const TriangleMesh cloth = make_grid(6, 6);
  const BodyTopology topology = build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count()));
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Vertices end = cloth.vertices;
    end(7, 1) = bad;
    SweptBoxes boxes;
    compute_swept_vertex_boxes(cloth.vertices, end, 0.0, boxes);
    Bvh bvh({VolumeKind::Aabb, 2, 2.0});
    CHECK_THROWS_AS(bvh.build(topology, boxes, cloth.vertices, end), std::invalid_argument);
  }
  // Every triangle at one place (no split by surface area: the median split), triangles 1e-310 apart
  // (subnormal: bins too narrow to index), 1e-300 or 1e300 apart: still exactly the brute-force pairs.
  for (const double spread : {0.0, 1e-310, 1e-300, 1e300}) {
    TriangleMesh soup = cloth;
    for (Eigen::Index v = 0; v < soup.vertex_count(); ++v) soup.vertices.row(v) *= spread;
    const TestBody body(soup, soup.vertices, 0.0, {VolumeKind::Aabb, 2, 2.0});
    CandidateSet found, reference;
    find_self_candidates(body.view(0), {false, nullptr}, found);
    brute_force_self_candidates(body.view(0), reference);
    check_same(sorted(found), sorted(reference));
  }
}
