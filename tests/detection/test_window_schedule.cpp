// The earliest-impact search's windows: consecutive dyadic parts that cover the step, a first window from the motion,
// longer windows when candidates grow slower than the length (pairs close all the time), shorter ones when they grow
// faster (a fast motion), and the mesh's relative motion.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <functional>
#include <vector>

#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/window_schedule.hpp"

using clothcd::detail::WindowSchedule;

namespace {

// The lengths of the windows a schedule makes until the step is covered, with `candidates(from, to)` as each
// window's count; checks that the windows are consecutive, dyadic (exact powers of two but the last) and cover [0, 1].
std::vector<double> lengths(double motion, double fixed_cost, const std::function<double(double, double)>& candidates) {
  WindowSchedule window(motion, fixed_cost);
  std::vector<double> found;
  double covered = 0.0;
  while (true) {
    REQUIRE(window.from() == covered);
    REQUIRE(window.to() > window.from());
    REQUIRE(window.to() <= 1.0);
    const double length = window.to() - window.from();
    int exponent = 0;
    if (!window.last()) CHECK(std::frexp(length, &exponent) == 0.5);  // a power of two
    CHECK(length >= 0x1p-10);
    found.push_back(length);
    covered = window.to();
    if (window.last()) break;
    window.advance(candidates(window.from(), window.to()));
    REQUIRE(found.size() < 2000);
  }
  CHECK(covered == 1.0);
  return found;
}

}  // namespace

TEST_CASE("window schedule: the first window from the motion", "[detection][earliest]") {
  const auto first = [](double motion) { return WindowSchedule(motion, 1000.0).to(); };
  CHECK(first(0.0) == 0x1p-4);
  CHECK(first(0.3) == 0x1p-4);
  CHECK(first(8.0) == 0x1p-4);   // half an edge in 1/16 of the step
  CHECK(first(8.5) == 0x1p-5);
  CHECK(first(20.0) == 0x1p-6);  // 1/64 of the step moves 0.31 edges
  CHECK(first(1e9) == 0x1p-10);
  CHECK(first(std::numeric_limits<double>::infinity()) == 0x1p-10);
}

TEST_CASE("window schedule: pairs close all the time make few long windows", "[detection][earliest]") {
  // A million candidates in any window, a few more in longer ones: 1/16, 1/8, then 8 times longer, to the end.
  const std::vector<double> found =
      lengths(0.3, 1e5, [](double from, double to) { return 1e6 + 1e5 * (to - from); });
  CHECK(found == std::vector<double>{0x1p-4, 0x1p-3, 1.0 - 0x1p-4 - 0x1p-3});
}

TEST_CASE("window schedule: a fast motion keeps short windows", "[detection][earliest]") {
  // Candidates growing with the square of the length: per unit of time (1000 + 4e6 L^2) / L is least at L = 1/64.
  const std::vector<double> found = lengths(20.0, 1000.0, [](double from, double to) {
    return 4e6 * (to - from) * (to - from);
  });
  REQUIRE(found.size() > 3);
  CHECK(found[0] == 0x1p-6);
  CHECK(found[1] == 0x1p-5);
  for (std::size_t k = 2; k + 1 < found.size(); ++k) CHECK(found[k] == 0x1p-6);
}

TEST_CASE("window schedule: a growth between linear and square doubles, a falling count grows fastest",
          "[detection][earliest]") {
  const std::vector<double> linear = lengths(0.0, 1.0, [](double from, double to) { return 1e4 * (to - from); });
  CHECK(linear == std::vector<double>{0x1p-4, 0x1p-3, 0x1p-2, 1.0 - 0x1p-4 - 0x1p-3 - 0x1p-2});  // the rest joins
  const std::vector<double> falling = lengths(0.0, 1.0, [](double from, double) { return 1e4 * (1.0 - from); });
  CHECK(falling == std::vector<double>{0x1p-4, 0x1p-3, 1.0 - 0x1p-4 - 0x1p-3});
  const std::vector<double> none = lengths(0.0, 1.0, [](double, double) { return 0.0; });
  CHECK(none.size() == 3);
}

TEST_CASE("window schedule: relative motion of a mesh", "[detection][earliest]") {
  const clothcd::TriangleMesh grid = clothcd::make_grid(4, 4, 1.0, 1.0);  // edges 1/4 and diagonals
  const clothcd::broadphase::BodyTopology topology =
      clothcd::broadphase::build_body_topology(grid.faces, static_cast<int>(grid.vertex_count()));
  double edges = 0.0;
  for (int e = 0; e < topology.edge_count(); ++e) {
    edges += (grid.vertices.row(topology.edges[2 * e]) - grid.vertices.row(topology.edges[2 * e + 1])).norm();
  }
  const double mean_edge = edges / topology.edge_count();
  CHECK(clothcd::detail::relative_motion(topology, grid.vertices, grid.vertices) == 0.0);
  clothcd::Vertices moved = grid.vertices;
  moved.col(1).array() += 3.0;
  CHECK(clothcd::detail::relative_motion(topology, grid.vertices, moved) == Approx(3.0 / mean_edge));
  clothcd::Vertices collapsed = clothcd::Vertices::Zero(grid.vertices.rows(), 3);
  CHECK(std::isinf(clothcd::detail::relative_motion(topology, collapsed, moved)));
}

TEST_CASE("window schedule: extreme counts still cover the step with valid windows", "[detection][earliest]") {
  // Counts jumping by twelve orders of magnitude, alternating with zero, or growing without bound: every window is
  // still a power of two of at least 2^-10 (checked in lengths()), and the windows end at 1.
  for (const double motion : {0.0, 3.0, 1e300}) {
    lengths(motion, 1.0, [](double from, double) { return from < 0.2 ? 1.0 : 1e12; });
    lengths(motion, 1e6, [](double from, double) { return static_cast<int>(from * 1024) % 2 == 0 ? 0.0 : 1e9; });
    lengths(motion, 1e-300, [](double, double to) { return std::exp(700.0 * to); });
    lengths(motion, 1.0, [](double from, double to) { return 1e300 * (to - from) * (to - from) * (to - from); });
  }
}
