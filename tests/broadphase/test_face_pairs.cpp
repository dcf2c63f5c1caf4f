// Face pair searches (SearchedPairs::FaceFace) find exactly the brute-force face pairs: every hierarchy kind, leaf
// size, SIMD level, serial and parallel, on a cloth draped over an obstacle, a folded cloth, seeded random soups and
// two bodies; faces sharing vertices are paired, a face never with itself, each pair once; a face pair search
// restricted to moved vertices is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/collecting_sink.hpp"
#include "broadphase_scenes.hpp"
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

TraversalSettings face_settings(bool parallel) {
  TraversalSettings settings;
  settings.parallel = parallel;
  settings.pairs = SearchedPairs::FaceFace;
  return settings;
}

// The search's face pairs are the reference's, without duplicates, and nothing else is produced.
void check_same_faces(const CandidateSet& found, const CandidateSet& reference) {
  CHECK(found.vertex_face.empty());
  CHECK(found.edge_edge.empty());
  CHECK(std::adjacent_find(found.face_face.begin(), found.face_face.end()) == found.face_face.end());
  CHECK(found.face_face.size() == reference.face_face.size());
  CHECK(found.face_face == reference.face_face);
}

// Every face pair within one body is ordered (face_a < face_b) and never a face with itself.
void check_ordered(const CandidateSet& found) {
  for (const FaceFaceCandidate& c : found.face_face) {
    CHECK(c.body_a == c.body_b);
    CHECK(c.face_a < c.face_b);
  }
}

// Self and pair face searches of the two bodies against the brute force, at every SIMD level the CPU runs.
void check_scene(const TestBody& first, const TestBody& second, bool parallel) {
  CandidateSet self_reference, pair_reference;
  brute_force_self_candidates(first.view(0), self_reference, SearchedPairs::FaceFace);
  brute_force_pair_candidates(first.view(0), second.view(1), pair_reference, SearchedPairs::FaceFace);
  REQUIRE(self_reference.face_face.size() > 0);
  REQUIRE(pair_reference.face_face.size() > 0);
  CHECK(self_reference.vertex_face.empty());
  CHECK(pair_reference.edge_edge.empty());
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    CandidateSet self_found, pair_found;
    find_self_candidates(first.view(0), face_settings(parallel), self_found);
    check_ordered(self_found);
    check_same_faces(sorted(self_found), sorted(self_reference));
    find_pair_candidates(first.view(0), second.view(1), face_settings(parallel), pair_found);
    check_same_faces(sorted(pair_found), sorted(pair_reference));
  }
}

}  // namespace

TEST_CASE("face pair searches match brute force on a cloth draped over obstacles", "[broadphase][faces]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const int leaf = GENERATE(1, 3, 32);  // 32 (the default): leaves span several groups of the packed tests
  const bool parallel = GENERATE(false, true);
  const int seed = GENERATE(1, 2);
  std::mt19937 rng(seed);
  const TriangleMesh cloth = draped_cloth(13);
  const TriangleMesh obstacle = seed == 1 ? make_uv_sphere(1.0, 14, 8) : make_box(Eigen::Vector3d(0.8, 0.9, 0.7));
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.08, rng), 0.01 * seed, {kinds.cloth, leaf});
  TestBody obstacle_body(obstacle, jitter(obstacle.vertices, 0.02, rng), 0.01 * seed, {kinds.obstacle, leaf});
  check_scene(cloth_body, obstacle_body, parallel);
}

TEST_CASE("face pair searches match brute force on a folded cloth searched in tasks", "[broadphase][faces]") {
  const bool spheres = GENERATE(false, true);
  const bool parallel = GENERATE(false, true);
  std::mt19937 rng(31);
  TriangleMesh cloth = draped_cloth(40);
  for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
    cloth.vertices(v, 1) += 0.05 * std::sin(9.0 * cloth.vertices(v, 0));
  }
  const TriangleMesh obstacle = make_uv_sphere(1.0, 20, 10);
  const VolumeKind kind = spheres ? VolumeKind::Sphere : VolumeKind::Aabb;
  TestBody cloth_body(cloth, jitter(cloth.vertices, 0.02, rng), 0.01, {kind, 16});
  TestBody obstacle_body(obstacle, obstacle.vertices, 0.01, {kind, 16});
  REQUIRE(cloth_body.topology.face_count() > 2048);  // the root's halves are searched as tasks of their own
  check_scene(cloth_body, obstacle_body, parallel);
}

TEST_CASE("face pair searches match brute force on random triangle soups", "[broadphase][faces][random]") {
  const auto kinds =
      GENERATE(KindPair{VolumeKind::Aabb, VolumeKind::Aabb}, KindPair{VolumeKind::Sphere, VolumeKind::Sphere},
               KindPair{VolumeKind::Aabb, VolumeKind::Obb});
  const int seed = GENERATE(range(40, 46));
  // Far from the origin the single-precision pre-selection is much coarser than the features; only the
  // double-precision boxes decide.
  const double offset = GENERATE(0.0, 3.0e7);
  std::mt19937 rng(seed);
  TriangleMesh a = random_soup(60, 90, rng);
  TriangleMesh b = random_soup(50, 70, rng);
  b.vertices.array() += 0.3;
  a.vertices.array() += offset;
  b.vertices.array() += offset;
  TestBody body_a(a, jitter(a.vertices, 0.05, rng), 0.0, {kinds.cloth, 1 + seed % 3});
  TestBody body_b(b, jitter(b.vertices, 0.05, rng), 0.001, {kinds.obstacle, 1 + seed % 4});
  check_scene(body_a, body_b, seed % 2 == 0);
}

TEST_CASE("face pair searches pair faces that share vertices, each pair once", "[broadphase][faces]") {
  // A flat, still grid: every face's box touches those of the faces around it, all of which share a vertex with it.
  const TriangleMesh cloth = make_grid(12, 12);
  TestBody body(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  CandidateSet found;
  find_self_candidates(body.view(0), face_settings(true), found);
  found = sorted(found);
  check_ordered(found);
  auto shares_vertex = [&](int f, int h) {
    for (int k = 0; k < 3; ++k) {
      if (body.topology.face_has_vertex(h, body.topology.faces(f, k))) return true;
    }
    return false;
  };
  for (int f = 0; f < body.topology.face_count(); ++f) {
    for (int h = f + 1; h < body.topology.face_count(); ++h) {
      if (!shares_vertex(f, h)) continue;
      const FaceFaceCandidate pair{0, f, 0, h};
      CHECK(std::binary_search(found.face_face.begin(), found.face_face.end(), pair));
    }
  }
  CandidateSet reference;
  brute_force_self_candidates(body.view(0), reference, SearchedPairs::FaceFace);
  check_same_faces(found, sorted(reference));
}

TEST_CASE("a face pair search restricted to moved vertices is refused", "[broadphase][faces][moved]") {
  const TriangleMesh cloth = make_grid(6, 6);
  TestBody a(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  TestBody b(cloth, cloth.vertices, 0.0, {VolumeKind::Aabb, 2});
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(a.topology.vertex_count), 0);
  moved[3] = 1;
  TraversalSettings settings = face_settings(false);
  settings.moved_vertices = &moved;
  CandidateSet out;
  CHECK_THROWS_AS(find_self_candidates(a.view(0), settings, out), std::invalid_argument);
  CHECK_THROWS_AS(find_pair_candidates(a.view(0), b.view(1), settings, out), std::invalid_argument);
  CHECK(out.size() == 0);
}
