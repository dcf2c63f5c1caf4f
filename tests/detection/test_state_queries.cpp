// The questions of one state (proximity, minimum_distance, intersections) against brute-force references in exact
// arithmetic, on seeded crumpled cloths, a cloth over a sphere, pairs at exactly the distance and scales from 1e-6 to
// 1e6; one thread against TBB; bad input; interleaving with the steps of detect().
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "cloth_over_sphere.hpp"
#include "state_reference.hpp"

namespace clothcd {
namespace {

// A grid cloth crumpled by seeded noise of `amplitude` (relative to its width 1) and scaled by `scale`.
TriangleMesh crumpled_cloth(int n, double amplitude, std::uint32_t seed, double scale = 1.0) {
  TriangleMesh cloth = make_grid(n, n, 1.0, 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-amplitude, amplitude);
  for (Eigen::Index v = 0; v < cloth.vertices.rows(); ++v) {
    const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2);
    cloth.vertices(v, 1) = 0.3 * std::sin(9.0 * x) * std::cos(7.0 * z) + noise(rng);
    cloth.vertices(v, 0) = 0.4 * x + noise(rng);  // squeezed so that folds come close
    cloth.vertices(v, 2) += noise(rng);
  }
  cloth.vertices *= scale;
  return cloth;
}

struct StateCase {
  TriangleMesh cloth;
  std::vector<TriangleMesh> obstacles;
};

CollisionDetector make_detector(const StateCase& c, bool parallel, HierarchyKind hierarchy = HierarchyKind::Aabb) {
  DetectorSettings settings;
  settings.parallel = parallel;
  settings.hierarchy = hierarchy;
  settings.max_leaf_faces = 4;
  CollisionDetector detector(c.cloth.faces, static_cast<int>(c.cloth.vertex_count()), settings);
  for (const TriangleMesh& o : c.obstacles) detector.add_obstacle(o);
  return detector;
}

// Checks proximity() against the reference: the same pairs exactly, distances within the stated error, exact types.
void check_proximity(const StateCase& c, double distance) {
  const std::vector<test::StateBody> bodies = test::state_bodies(c.cloth, c.cloth.vertices, c.obstacles);
  const std::vector<test::ReferencePair> expected = test::reference_proximity(bodies, distance);
  std::vector<Proximity> first;
  for (const bool parallel : {false, true}) {
    for (const HierarchyKind hierarchy : {HierarchyKind::Aabb, HierarchyKind::SphereRootAabb, HierarchyKind::AabbObb}) {
      CollisionDetector detector = make_detector(c, parallel, hierarchy);
      const std::vector<Proximity> found = detector.proximity(c.cloth.vertices, distance);
      REQUIRE(found.size() == expected.size());
      std::set<std::array<std::int64_t, 9>> expected_ids;
      for (const test::ReferencePair& p : expected) expected_ids.insert(test::pair_id(p.kind, p.vertices));
      for (std::size_t i = 0; i < found.size(); ++i) {
        const Proximity& p = found[i];
        REQUIRE(expected_ids.count(test::pair_id(p.kind, p.vertices)) == 1);
        const test::ReferencePair& r = *std::find_if(expected.begin(), expected.end(), [&](const auto& e) {
          return test::pair_id(e.kind, e.vertices) == test::pair_id(p.kind, p.vertices);
        });
        CHECK(p.type == r.type);
        const double exact = std::sqrt(r.squared_distance.get_d());
        CHECK(std::abs(p.distance - exact) <= 2.0 * kDistanceRelativeError * exact + 1e-300);
        CHECK(p.distance < distance);
      }
      // Every hierarchy and thread count gives the same list, bit for bit.
      if (first.empty()) first = found;
      REQUIRE(found.size() == first.size());
      for (std::size_t i = 0; i < found.size(); ++i) {
        CHECK(test::pair_id(found[i].kind, found[i].vertices) == test::pair_id(first[i].kind, first[i].vertices));
        CHECK(found[i].distance == first[i].distance);
        CHECK(found[i].parameters == first[i].parameters);
      }
    }
  }
}

}  // namespace

TEST_CASE("proximity equals the exact brute-force pairs on crumpled cloths", "[state][proximity]") {
  const std::uint32_t seed = GENERATE(1u, 2u, 3u);
  const double scale = GENERATE(1e-6, 1.0, 1e6);
  StateCase c{crumpled_cloth(9, 0.05, seed, scale), {}};
  check_proximity(c, 0.02 * scale);
  check_proximity(c, 0.1 * scale);
}

TEST_CASE("proximity equals the exact brute-force pairs of a cloth over a sphere", "[state][proximity]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.13);
  StateCase c{step.cloth, {step.obstacle}};
  c.cloth.vertices = step.end;
  check_proximity(c, 0.05);
  check_proximity(c, 0.2);
}

TEST_CASE("a pair at exactly the distance is not within it, one a little closer is", "[state][proximity]") {
  // A flat cloth at y = 0 under one obstacle triangle at height h: the vertices under the triangle are exactly h away.
  for (const double h : {0.25, 0.1, 0.3}) {  // dyadic and decimal distances
    StateCase c{make_grid(5, 5, 1.0, 1.0), {}};
    TriangleMesh roof;
    roof.vertices = Vertices(3, 3);
    roof.vertices << -0.3, h, -0.3, 0.3, h, -0.3, 0.0, h, 0.3;
    roof.faces = Faces(1, 3);
    roof.faces << 0, 1, 2;
    c.obstacles.push_back(roof);
    CollisionDetector detector = make_detector(c, false);
    const std::vector<Proximity> at = detector.proximity(c.cloth.vertices, h);
    for (const Proximity& p : at) CHECK(p.distance < h);
    const std::vector<test::StateBody> bodies = test::state_bodies(c.cloth, c.cloth.vertices, c.obstacles);
    CHECK(at.size() == test::reference_proximity(bodies, h).size());
    const double above = std::nextafter(h, 1.0);
    const std::vector<Proximity> just = detector.proximity(c.cloth.vertices, above);
    CHECK(just.size() == test::reference_proximity(bodies, above).size());
    CHECK(just.size() > at.size());
  }
}

TEST_CASE("minimum_distance is the exact minimum over the pairs", "[state][minimum-distance]") {
  const std::uint32_t seed = GENERATE(4u, 5u, 6u);
  const double scale = GENERATE(1e-6, 1.0, 1e6);
  StateCase c{crumpled_cloth(8, 0.05, seed, scale), {}};
  const std::vector<test::StateBody> bodies = test::state_bodies(c.cloth, c.cloth.vertices, c.obstacles);
  mpq_class smallest = -1;
  test::for_each_reference_pair(bodies, [&](const test::ReferencePair& p) {
    if (smallest < 0 || p.squared_distance < smallest) smallest = p.squared_distance;
  });
  const double exact = std::sqrt(smallest.get_d());
  for (const bool parallel : {false, true}) {
    CollisionDetector detector = make_detector(c, parallel);
    const MinimumDistance m = detector.minimum_distance(c.cloth.vertices);
    REQUIRE(m.found);
    CHECK(std::abs(m.distance - exact) <= 2.0 * kDistanceRelativeError * exact + 1e-300);
    CHECK(m.pair.distance == m.distance);
    // With an upper bound below the minimum nothing is found; above it the same answer.
    const MinimumDistance none = detector.minimum_distance(c.cloth.vertices, 0.5 * exact);
    CHECK_FALSE(none.found);
    const MinimumDistance same = detector.minimum_distance(c.cloth.vertices, 2.0 * exact);
    REQUIRE(same.found);
    CHECK(same.distance == m.distance);
    CHECK(test::pair_id(same.pair.kind, same.pair.vertices) == test::pair_id(m.pair.kind, m.pair.vertices));
  }
}

TEST_CASE("intersections equal the exact brute-force face pairs", "[state][intersections]") {
  const std::uint32_t seed = GENERATE(7u, 8u, 9u);
  const double amplitude = GENERATE(0.02, 0.15);
  StateCase c{crumpled_cloth(8, amplitude, seed), {}};
  const test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  c.obstacles.push_back(step.obstacle);
  c.cloth.vertices.col(1).array() += 0.55;  // into the sphere's top
  const std::vector<test::StateBody> bodies = test::state_bodies(c.cloth, c.cloth.vertices, c.obstacles);
  const auto expected = test::reference_intersections(bodies);
  for (const bool parallel : {false, true}) {
    CollisionDetector detector = make_detector(c, parallel);
    const std::vector<FaceIntersection> found = detector.intersections(c.cloth.vertices);
    REQUIRE(found.size() == expected.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
      const FaceIntersection& f = found[i];
      CHECK(std::array<std::int32_t, 4>{f.bodies[0], f.faces[0], f.bodies[1], f.faces[1]} == expected[i]);
    }
    CHECK(detector.is_intersection_free(c.cloth.vertices) == expected.empty());
  }
}

TEST_CASE("state queries reject bad input and leave the detector usable", "[state]") {
  StateCase c{crumpled_cloth(5, 0.05, 1), {}};
  CollisionDetector detector = make_detector(c, false);
  Vertices wrong(3, 3);
  wrong.setZero();
  CHECK_THROWS_AS(detector.proximity(wrong, 0.1), std::invalid_argument);
  Vertices nan = c.cloth.vertices;
  nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(detector.proximity(nan, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(detector.minimum_distance(nan), std::invalid_argument);
  CHECK_THROWS_AS(detector.intersections(nan), std::invalid_argument);
  CHECK_THROWS_AS(detector.is_intersection_free(nan), std::invalid_argument);
  for (const double d : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    CHECK_THROWS_AS(detector.proximity(c.cloth.vertices, d), std::invalid_argument);
  }
  CHECK_THROWS_AS(detector.minimum_distance(c.cloth.vertices, 0.0), std::invalid_argument);
  const std::vector<test::StateBody> bodies = test::state_bodies(c.cloth, c.cloth.vertices, c.obstacles);
  CHECK(detector.proximity(c.cloth.vertices, 0.1).size() == test::reference_proximity(bodies, 0.1).size());
}

TEST_CASE("state queries stop at the budget and on cancel", "[state]") {
  StateCase c{crumpled_cloth(9, 0.05, 2), {}};
  DetectorSettings settings;
  settings.max_collisions = 5;
  settings.block_pairs = 16;
  CollisionDetector detector(c.cloth.faces, static_cast<int>(c.cloth.vertex_count()), settings);
  CHECK_THROWS_AS(detector.proximity(c.cloth.vertices, 0.2), CollisionBudgetExceeded);
  detector.set_cancel_check([] { return true; });
  CHECK_THROWS_AS(detector.proximity(c.cloth.vertices, 0.01), DetectionCancelled);
  CHECK_THROWS_AS(detector.intersections(c.cloth.vertices), DetectionCancelled);
  detector.set_cancel_check({});
  CHECK_NOTHROW(detector.proximity(c.cloth.vertices, 1e-4));
}

TEST_CASE("a state query between two steps leaves the re-test of the step intact", "[state][reuse]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.13);
  StateCase c{step.cloth, {step.obstacle}};
  DetectorSettings settings;
  CollisionDetector interleaved(c.cloth.faces, static_cast<int>(c.cloth.vertex_count()), settings);
  interleaved.add_obstacle(step.obstacle);
  CollisionDetector fresh(c.cloth.faces, static_cast<int>(c.cloth.vertex_count()), settings);
  fresh.add_obstacle(step.obstacle);
  interleaved.detect(step.cloth.vertices, step.end);
  interleaved.proximity(step.end, 0.05);
  interleaved.minimum_distance(step.cloth.vertices);
  interleaved.intersections(step.end);
  Vertices moved = step.end;
  moved.row(7) += Eigen::RowVector3d(0.0, 0.02, 0.0);
  const std::vector<Collision> again = interleaved.detect(step.cloth.vertices, moved);
  CHECK(interleaved.stats().reused > 0);
  const std::vector<Collision> expected = fresh.detect(step.cloth.vertices, moved);
  REQUIRE(again.size() == expected.size());
  for (std::size_t i = 0; i < again.size(); ++i) {
    CHECK(test::pair_id(again[i].kind, again[i].vertices) == test::pair_id(expected[i].kind, expected[i].vertices));
    CHECK(again[i].toi == expected[i].toi);
  }
}

}  // namespace clothcd
