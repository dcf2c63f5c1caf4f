// Degenerate steps, as a simulation that explodes makes them: each has a clear outcome, an answer within the collision
// budget or CollisionBudgetExceeded, with the peak resident memory of the call bounded (the process's own counters);
// after a failed call the detector answers the next step as a fresh detector would. CTest also runs the
// [degenerate] cases under an address-space limit (degenerate_steps_under_memory_limit).
#include <catch2/catch.hpp>

#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "broadphase/body_topology.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/cloth_over_sphere.hpp"
#include "detection/peak_memory.hpp"
#include "detection/same_collisions.hpp"

using namespace clothcd;

namespace {

// The memory a call may take: the promised bound per collision, plus what does not grow with the collisions (the
// hierarchy, the threads' blocks and chunks, the allocator's own, with what earlier tests of the process left in
// its arenas).
constexpr long kBytesPerCollision = 120;
constexpr long kFixedBytes = 64L << 20;

// Every vertex of `mesh` at its centroid.
Vertices collapsed(const TriangleMesh& mesh) {
  Vertices point = mesh.vertices;
  const Eigen::RowVector3d centroid = mesh.vertices.colwise().mean();
  for (Eigen::Index v = 0; v < point.rows(); ++v) point.row(v) = centroid;
  return point;
}

// The peak resident bytes of `call` above the resident bytes before it.
template <class Call>
long peak_bytes_of(const Call& call) {
  REQUIRE(test::reset_peak_memory());
  const long before = test::resident_bytes();
  call();
  return test::peak_resident_bytes() - before;
}

// Collisions a stopped search may have found past the budget: each thread checks it before each block, so at most one
// block of pairs per thread.
long budget_overshoot(const DetectorSettings& settings) {
  return static_cast<long>(tbb::this_task_arena::max_concurrency()) * settings.block_pairs;
}

// The same step through a detector that culls nothing (the filters never drop a colliding pair), with `obstacle` when
// given.
std::vector<Collision> unculled_collisions(const TriangleMesh& mesh, const Vertices& start, const Vertices& end,
                                           const TriangleMesh* obstacle = nullptr) {
  DetectorSettings settings;
  settings.culling = CullingMode::None;
  CollisionDetector detector(mesh.faces, static_cast<int>(mesh.vertex_count()), settings);
  if (obstacle != nullptr) detector.add_obstacle(*obstacle);
  return detector.detect(start, end);
}

void check_finite(const std::vector<Collision>& collisions) {
  for (const Collision& c : collisions) {
    CHECK(c.toi >= 0.0);
    CHECK(c.toi <= 1.0);
    CHECK(std::isfinite(c.parameters[0]));
    CHECK(std::isfinite(c.parameters[1]));
    CHECK(c.normal.allFinite());
  }
}

}  // namespace

TEST_CASE("a collapsing grid within the budget is answered in at most 120 bytes per collision",
          "[detection][degenerate][memory]") {
  const TriangleMesh grid = make_grid(20, 20);
  const Vertices point = collapsed(grid);
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()));
  std::size_t collisions = 0;
  const long peak = peak_bytes_of([&] { collisions = detector.detect(grid.vertices, point).size(); });
  // Enough collisions that their memory, not the fixed part, decides the bound.
  REQUIRE(collisions > 500'000);
  CHECK(collisions <= static_cast<std::size_t>(DetectorSettings{}.max_collisions));
  if (test::kMemoryCountersMeaningful) CHECK(peak <= kBytesPerCollision * static_cast<long>(collisions) + kFixedBytes);
}

TEST_CASE("collapsing grids stop promptly at the collision budget, in bounded memory",
          "[detection][degenerate][memory]") {
  const int n = GENERATE(40, 80, 160);
  const TriangleMesh grid = make_grid(n, n);
  const Vertices point = collapsed(grid);
  DetectorSettings settings;
  settings.max_collisions = 250'000;
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()), settings);
  long reached = 0;
  const long peak = peak_bytes_of([&] {
    try {
      (void)detector.detect(grid.vertices, point);
    } catch (const CollisionBudgetExceeded& e) {
      reached = e.collisions();
      CHECK(e.max_collisions() == settings.max_collisions);
      CHECK(std::string(e.what()).find("max_collisions") != std::string::npos);
      CHECK(std::string(e.what()).find(std::to_string(e.collisions())) != std::string::npos);
    }
  });
  INFO("grid " << n << " x " << n << ": stopped at " << reached << " collisions, peak " << (peak >> 20) << " MB");
  REQUIRE(reached > settings.max_collisions);
  // Stopped as soon as the count passed the budget: n = 40 alone has 15.6 million collisions.
  CHECK(reached <= settings.max_collisions + budget_overshoot(settings));
  if (test::kMemoryCountersMeaningful) CHECK(peak <= kBytesPerCollision * settings.max_collisions + kFixedBytes);
}

TEST_CASE("the earliest-impact search of a collapsing grid stops at the collision budget too",
          "[detection][degenerate][earliest]") {
  // Every pair touches at the end of the step, so every one must be examined: the budget ends it as it ends detect().
  const int n = GENERATE(40, 80);
  const TriangleMesh grid = make_grid(n, n);
  const Vertices point = collapsed(grid);
  DetectorSettings settings;
  settings.max_collisions = 250'000;
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()), settings);
  long reached = 0;
  try {
    (void)detector.earliest_impact(grid.vertices, point);
  } catch (const CollisionBudgetExceeded& e) {
    reached = e.collisions();
  }
  INFO("grid " << n << " x " << n << ": stopped at " << reached << " collisions");
  REQUIRE(reached > settings.max_collisions);
  CHECK(reached <= settings.max_collisions + budget_overshoot(settings));
  // The detector stays usable: a step moving the grid away has no contact.
  Vertices lifted = grid.vertices;
  lifted.col(1).array() += 0.5;
  const EarliestImpact free = detector.earliest_impact(grid.vertices, lifted);
  CHECK_FALSE(free.hit);
  CHECK(free.toi == 1.0);
}

TEST_CASE("after a failed call the detector answers like a fresh one, and a re-test reuses nothing of it",
          "[detection][degenerate][reuse]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  const auto fresh = [&](const Vertices& end) {
    CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()));
    detector.add_obstacle(step.obstacle);
    return detector.detect(step.cloth.vertices, end);
  };
  const std::vector<Collision> reference = fresh(step.end);
  REQUIRE(reference.size() > 10);

  DetectorSettings settings;
  settings.max_collisions = static_cast<long>(reference.size());  // the step fits exactly
  CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), settings);
  detector.add_obstacle(step.obstacle);
  // Same start positions as the steps below: a re-test of the failed call, were anything of it kept.
  CHECK_THROWS_AS(detector.detect(step.cloth.vertices, collapsed(step.cloth)), CollisionBudgetExceeded);
  test::check_same(detector.detect(step.cloth.vertices, step.end), reference);
  CHECK(detector.stats().reused == 0);
  CHECK(detector.stats().collisions == static_cast<long>(reference.size()));

  // A re-test after a good call still reuses its answer, and fails and recovers the same way.
  Vertices moved_end = step.end;
  moved_end(7, 1) -= 0.01;
  const std::vector<Collision> moved_reference = fresh(moved_end);
  if (moved_reference.size() <= reference.size()) {
    test::check_same(detector.detect(step.cloth.vertices, moved_end), moved_reference);
    CHECK(detector.stats().reused > 0);
  }
  CHECK_THROWS_AS(detector.detect(step.cloth.vertices, collapsed(step.cloth)), CollisionBudgetExceeded);
  test::check_same(detector.detect(step.cloth.vertices, step.end), reference);
  CHECK(detector.stats().reused == 0);
}

TEST_CASE("the collision budget is exact at its boundary", "[detection][degenerate]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  const bool parallel = GENERATE(false, true);
  DetectorSettings settings;
  settings.parallel = parallel;
  CollisionDetector unlimited(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), settings);
  unlimited.add_obstacle(step.obstacle);
  const long count = static_cast<long>(unlimited.detect(step.cloth.vertices, step.end).size());
  REQUIRE(count > 1);
  for (const long budget : {count, count - 1}) {
    settings.max_collisions = budget;
    CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), settings);
    detector.add_obstacle(step.obstacle);
    if (budget == count) {
      CHECK(static_cast<long>(detector.detect(step.cloth.vertices, step.end).size()) == count);
    } else {
      try {
        (void)detector.detect(step.cloth.vertices, step.end);
        FAIL("no CollisionBudgetExceeded");
      } catch (const CollisionBudgetExceeded& e) {
        CHECK(e.collisions() > budget);
        CHECK(e.collisions() <= count);
      }
    }
  }
}

TEST_CASE("all vertices coincident and still: every pair that shares no vertex collides at time 0",
          "[detection][degenerate]") {
  const TriangleMesh grid = make_grid(6, 6);
  const Vertices point = collapsed(grid);
  const broadphase::BodyTopology topology =
      broadphase::build_body_topology(grid.faces, static_cast<int>(grid.vertex_count()));
  long pairs = 0;
  for (int v = 0; v < topology.vertex_count; ++v) {
    for (int f = 0; f < topology.face_count(); ++f) pairs += topology.face_has_vertex(f, v) ? 0 : 1;
  }
  for (int e = 0; e < topology.edge_count(); ++e) {
    for (int g = e + 1; g < topology.edge_count(); ++g) pairs += topology.edges_share_vertex(e, g) ? 0 : 1;
  }
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()));
  const std::vector<Collision>& found = detector.detect(point, point);
  CHECK(static_cast<long>(found.size()) == pairs);
  for (const Collision& c : found) CHECK(c.toi == 0.0);
  check_finite(found);

  DetectorSettings small;
  small.max_collisions = pairs / 2;
  CollisionDetector limited(grid.faces, static_cast<int>(grid.vertex_count()), small);
  CHECK_THROWS_AS(limited.detect(point, point), CollisionBudgetExceeded);
}

TEST_CASE("one vertex flung across the scene: every collision is one of its pairs", "[detection][degenerate]") {
  const TriangleMesh grid = make_grid(16, 16);
  const int flung = 8 * 16 + 8;
  Vertices end = grid.vertices;
  end(flung, 0) += 1.0e3;  // in the plane, so that its faces sweep over the rest of the grid
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()));
  const std::vector<Collision>& found = detector.detect(grid.vertices, end);
  REQUIRE(!found.empty());
  for (const Collision& c : found) {
    bool has_flung = false;
    for (const VertexRef& r : c.vertices) has_flung = has_flung || r.vertex == flung;
    CHECK(has_flung);
  }
  check_finite(found);
  test::check_same(found, unculled_collisions(grid, grid.vertices, end));
}

TEST_CASE("every swept box spanning the scene: the answer, within the budget and its memory bound",
          "[detection][degenerate][memory]") {
  const TriangleMesh grid = make_grid(12, 12);
  Vertices end = grid.vertices;
  for (Eigen::Index v = 0; v < end.rows(); ++v) {  // each vertex to the mirror point through the centre, lifted
    end(v, 0) = -grid.vertices(v, 0);
    end(v, 1) = 0.25 * std::cos(7.0 * grid.vertices(v, 0));
    end(v, 2) = -grid.vertices(v, 2);
  }
  CollisionDetector detector(grid.faces, static_cast<int>(grid.vertex_count()));
  std::vector<Collision> found;
  const long peak = peak_bytes_of([&] { found = detector.detect(grid.vertices, end); });
  REQUIRE(!found.empty());
  if (test::kMemoryCountersMeaningful)  // and the copy in `found`
    CHECK(peak <= 2 * kBytesPerCollision * static_cast<long>(found.size()) + kFixedBytes);
  check_finite(found);
  test::check_same(found, unculled_collisions(grid, grid.vertices, end));
}

TEST_CASE("zero-length edges: an answer with finite fields, the same as without culling", "[detection][degenerate]") {
  test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  // Three vertices onto their neighbours: edges (and faces) of zero length, in both frames.
  for (const int v : {13, 66, 118}) {
    step.cloth.vertices.row(v + 1) = step.cloth.vertices.row(v);
    step.end.row(v + 1) = step.end.row(v);
  }
  CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()));
  detector.add_obstacle(step.obstacle);
  const std::vector<Collision>& found = detector.detect(step.cloth.vertices, step.end);
  REQUIRE(!found.empty());
  check_finite(found);
  test::check_same(found, unculled_collisions(step.cloth, step.cloth.vertices, step.end, &step.obstacle));
}

TEST_CASE("a NaN in the end positions mid-simulation is a clear error, and the next step is answered",
          "[detection][degenerate][errors]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()));
  detector.add_obstacle(step.obstacle);
  const std::vector<Collision> first = detector.detect(step.cloth.vertices, step.end);
  REQUIRE(!first.empty());
  Vertices broken = step.end;
  broken(17, 2) = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)detector.detect(step.cloth.vertices, broken);
    FAIL("no error on a NaN");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("NaN") != std::string::npos);
  }
  test::check_same(detector.detect(step.cloth.vertices, step.end), first);
}

TEST_CASE("a cancel check stops a long call, and the detector stays usable", "[detection][degenerate][cancel]") {
  const test::ClothOverSphere step = test::cloth_over_sphere(0.14);
  CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()));
  detector.add_obstacle(step.obstacle);
  std::atomic<long> checks{0};
  detector.set_cancel_check([&] { return ++checks > 20; });
  CHECK_THROWS_AS(detector.detect(step.cloth.vertices, collapsed(step.cloth)), DetectionCancelled);
  CHECK(checks > 20);

  // A check that never cancels changes nothing; without one, the detector answers as one that culls nothing.
  detector.set_cancel_check([] { return false; });
  const std::vector<Collision> checked = detector.detect(step.cloth.vertices, step.end);
  REQUIRE(!checked.empty());
  detector.set_cancel_check({});
  test::check_same(detector.detect(step.cloth.vertices, step.end), checked);
  test::check_same(checked, unculled_collisions(step.cloth, step.cloth.vertices, step.end, &step.obstacle));
}
