// Hand-made CCD cases, each with the reason for its expected answer; every case is checked on the exact reference, the
// fast path and the filters (a filter must never cull a colliding case).
#include <limits>
#include <string>

#include "ccd/ccd_test_support.hpp"

using clothcd::PairKind;
using clothcd::test::check_query;
using clothcd::test::make_query;
using clothcd::test::scaled;
using clothcd::test::Vector3d;
namespace ccd = clothcd::ccd;

namespace {

// The static unit right triangle in z = 0 with a vertex moving from `from` to `to`.
ccd::CcdQuery vertex_past_triangle(const Vector3d& from, const Vector3d& to) {
  const Vector3d f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0);
  return make_query(PairKind::VertexFace, {from, f0, f1, f2}, {to, f0, f1, f2});
}

// Static edge a from (-1,0,0) to (1,0,0); edge b moves from b_start to b_end.
ccd::CcdQuery edge_past_x_axis(const std::array<Vector3d, 2>& b_start, const std::array<Vector3d, 2>& b_end) {
  const Vector3d a0(-1, 0, 0), a1(1, 0, 0);
  return make_query(PairKind::EdgeEdge, {a0, a1, b_start[0], b_start[1]}, {a0, a1, b_end[0], b_end[1]});
}

}  // namespace

TEST_CASE("vertex through the face centre hits at mid-step", "[ccd][vertex-face]") {
  // The vertex crosses z = 0 at t = 1/2 at (0.25, 0.25), strictly inside the triangle.
  const auto query = vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1});
  check_query(query, true);
  const ccd::CcdResult result = ccd::continuous_collision(query);
  CHECK(result.toi <= 0.5);
  CHECK(result.toi > 0.5 - 1e-6);
  CHECK(result.parameters[0] == Approx(0.25));
  CHECK(result.parameters[1] == Approx(0.25));
  CHECK(result.normal.z() == Approx(1.0));  // from the face towards where the vertex came from
}

TEST_CASE("vertex passing beside the face misses", "[ccd][vertex-face]") {
  // Crosses the plane at (0.6, 0.6): x + y = 1.2 > 1, outside the triangle.
  check_query(vertex_past_triangle({0.6, 0.6, 1}, {0.6, 0.6, -1}), false);
  // Never reaches the plane.
  check_query(vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, 0.5}), false);
}

TEST_CASE("touching exactly at t = 0 and at t = 1 counts", "[ccd][vertex-face]") {
  // Starts on the face and leaves: contact at t = 0 only.
  const auto leaving = vertex_past_triangle({0.25, 0.25, 0}, {0.25, 0.25, 1});
  check_query(leaving, true);
  CHECK(ccd::continuous_collision(leaving).toi == 0.0);
  // Arrives on the face exactly at the end of the step.
  check_query(vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, 0}), true);
  // Arrives just short of it.
  check_query(vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, 0x1p-40}), false);
}

TEST_CASE("vertex through an edge or a corner of the face hits (closed triangle)", "[ccd][vertex-face]") {
  check_query(vertex_past_triangle({0.5, 0, 1}, {0.5, 0, -1}), true);      // midpoint of edge f0 f1
  check_query(vertex_past_triangle({0.5, 0.5, 1}, {0.5, 0.5, -1}), true);  // midpoint of the hypotenuse
  check_query(vertex_past_triangle({1, 0, 1}, {1, 0, -1}), true);          // corner f1
  // One ulp-scale step beyond the hypotenuse: outside, and only exact arithmetic can tell.
  check_query(vertex_past_triangle({0.5, 0.5 + 0x1p-50, 1}, {0.5, 0.5 + 0x1p-50, -1}), false);
}

TEST_CASE("zero-area face: only its segment can be hit", "[ccd][vertex-face]") {
  const Vector3d f0(0, 0, 0), f1(1, 0, 0), f2(2, 0, 0);  // collinear: the face is the segment [0, 2] on the x axis
  check_query(make_query(PairKind::VertexFace, {Vector3d(0.5, 1, 0), f0, f1, f2}, {Vector3d(0.5, -1, 0), f0, f1, f2}),
              true);  // passes through (0.5, 0, 0) on the segment
  check_query(
      make_query(PairKind::VertexFace, {Vector3d(0.5, 1, 0.125), f0, f1, f2}, {Vector3d(0.5, -1, 0.125), f0, f1, f2}),
      false);  // passes 0.125 above it
  check_query(make_query(PairKind::VertexFace, {Vector3d(3, 1, 0), f0, f1, f2}, {Vector3d(3, -1, 0), f0, f1, f2}),
              false);  // crosses the line beyond the segment's end
}

TEST_CASE("coplanar for the whole step: decided in the plane", "[ccd][vertex-face]") {
  // Everything stays in z = 0, so D(t) is identically zero; the vertex slides into the triangle.
  check_query(vertex_past_triangle({2, 0.25, 0}, {0.1, 0.25, 0}), true);
  // Slides parallel to the triangle's hypotenuse, outside it.
  check_query(vertex_past_triangle({2, 2, 0}, {-1, 2, 0}), false);
}

TEST_CASE("tiny and huge coordinates behave like unit ones", "[ccd][vertex-face][edge-edge]") {
  for (const double scale : {0x1p-27, 0x1p27, 1e-8, 1e8}) {
    INFO("scale " << scale);
    check_query(scaled(vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1}), scale), true);
    check_query(scaled(vertex_past_triangle({0.6, 0.6, 1}, {0.6, 0.6, -1}), scale), false);
    check_query(
        scaled(edge_past_x_axis({Vector3d(0, -1, 1), Vector3d(0, 1, 1)}, {Vector3d(0, -1, -1), Vector3d(0, 1, -1)}),
               scale),
        true);
  }
}

TEST_CASE("thickness with coordinates beyond the fast range is a prompt conservative hit", "[ccd][thickness]") {
  // At 2^200 the distances could overflow; the answer is a conservative hit at once (the exact path's rational root
  // isolation could take minutes at these magnitudes and would only change the state label).
  ccd::CcdSettings settings;
  settings.thickness = 1.0;
  const ccd::CcdResult result = ccd::continuous_collision(
      scaled(vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1}), 0x1p200), settings);
  CHECK(result.hit);
  CHECK(result.state == ccd::CcdState::ConservativeHit);
  CHECK(result.toi == 0.0);
}

TEST_CASE("crossing edges hit, edges passing beyond an end miss", "[ccd][edge-edge]") {
  // Edge b sweeps down through the x axis at t = 1/2 crossing it at the origin.
  const auto crossing =
      edge_past_x_axis({Vector3d(0, -1, 1), Vector3d(0, 1, 1)}, {Vector3d(0, -1, -1), Vector3d(0, 1, -1)});
  check_query(crossing, true);
  CHECK(ccd::continuous_collision(crossing, clothcd::test::exact_settings()).toi == Approx(0.5).margin(1e-6));
  // Same motion at x = 1.5, beyond a's end at x = 1.
  check_query(
      edge_past_x_axis({Vector3d(1.5, -1, 1), Vector3d(1.5, 1, 1)}, {Vector3d(1.5, -1, -1), Vector3d(1.5, 1, -1)}),
      false);
  // Exactly at a's end point (x = 1): touching counts.
  check_query(edge_past_x_axis({Vector3d(1, -1, 1), Vector3d(1, 1, 1)}, {Vector3d(1, -1, -1), Vector3d(1, 1, -1)}),
              true);
}

TEST_CASE("parallel edges: D(t) is identically zero", "[ccd][edge-edge]") {
  // b parallel to a, sweeping through it in the plane z = 0: overlapping segments meet.
  check_query(
      edge_past_x_axis({Vector3d(-0.5, 1, 0), Vector3d(0.5, 1, 0)}, {Vector3d(-0.5, -1, 0), Vector3d(0.5, -1, 0)}),
      true);
  // Same sweep, but b lies beyond a's end along x: the segments never overlap.
  check_query(edge_past_x_axis({Vector3d(2, 1, 0), Vector3d(3, 1, 0)}, {Vector3d(2, -1, 0), Vector3d(3, -1, 0)}),
              false);
  // Parallel, in the plane z = 1 all the time.
  check_query(
      edge_past_x_axis({Vector3d(-0.5, 1, 1), Vector3d(0.5, 1, 1)}, {Vector3d(-0.5, -1, 1), Vector3d(0.5, -1, 1)}),
      false);
  // Collinear, sliding along the x axis into a.
  check_query(edge_past_x_axis({Vector3d(3, 0, 0), Vector3d(4, 0, 0)}, {Vector3d(0.5, 0, 0), Vector3d(1.5, 0, 0)}),
              true);
}

TEST_CASE("edge end points meeting at t = 0 or t = 1", "[ccd][edge-edge]") {
  // b's end point arrives exactly on a's end point (1, 0, 0) at t = 1.
  check_query(edge_past_x_axis({Vector3d(1, 1, 1), Vector3d(1, 2, 1)}, {Vector3d(1, 0, 0), Vector3d(1, 1, 0)}), true);
  // b starts touching a's interior at (0, 0, 0) and moves away.
  check_query(edge_past_x_axis({Vector3d(0, 0, 0), Vector3d(0, 1, 0)}, {Vector3d(0, 1, 1), Vector3d(0, 2, 1)}), true);
  // b stops 2^-45 short of a.
  check_query(edge_past_x_axis({Vector3d(0, 1, 1), Vector3d(0, 2, 1)}, {Vector3d(0, 0x1p-45, 0), Vector3d(0, 1, 0)}),
              false);
}

TEST_CASE("degenerate edge (a point) through the other edge", "[ccd][edge-edge]") {
  check_query(
      edge_past_x_axis({Vector3d(0.25, 1, 0), Vector3d(0.25, 1, 0)}, {Vector3d(0.25, -1, 0), Vector3d(0.25, -1, 0)}),
      true);
  check_query(edge_past_x_axis({Vector3d(0.25, 1, 0.5), Vector3d(0.25, 1, 0.5)},
                               {Vector3d(0.25, -1, 0.5), Vector3d(0.25, -1, 0.5)}),
              false);
}

TEST_CASE("thickness reports pairs that come within it, and only those", "[ccd][thickness]") {
  // The vertex descends to 1/64 above the face centre and stops there.
  const auto hover = vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, 1.0 / 64});
  CHECK_FALSE(ccd::continuous_collision(hover).hit);
  ccd::CcdSettings thick;
  thick.thickness = 1.0 / 32;
  const ccd::CcdResult within = ccd::continuous_collision(hover, thick);
  CHECK(within.hit);
  CHECK(within.state == ccd::CcdState::Hit);  // proven within the thickness, though never touching
  CHECK(within.toi <= 1.0);
  ccd::CcdSettings thin;
  thin.thickness = 1.0 / 256;
  CHECK_FALSE(ccd::continuous_collision(hover, thin).hit);
  // Neither filter may cull a pair that comes within the thickness.
  CHECK_FALSE(ccd::nonpenetration_filter_culls(hover, thick));
  CHECK_FALSE(ccd::projection_filter_culls(hover, thick));
  CHECK_FALSE(ccd::combined_filters_cull(hover, thick));
  // A real crossing stays a proven hit with thickness.
  const auto through = vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1});
  const ccd::CcdResult crossing = ccd::continuous_collision(through, thick);
  CHECK(crossing.state == ccd::CcdState::Hit);
  CHECK(crossing.toi <= 0.5);
}

TEST_CASE("invalid input: NaN coordinates and negative thickness", "[ccd][errors]") {
  auto query = vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1});
  query.end[2].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(ccd::validate_query(query), std::invalid_argument);
  CHECK_THROWS_AS(ccd::exact_collision_reference(query), std::invalid_argument);
  const ccd::CcdResult result = ccd::continuous_collision(query);
  CHECK(result.hit);
  CHECK(result.state == ccd::CcdState::ConservativeHit);
  ccd::CcdSettings negative;
  negative.thickness = -1.0;
  CHECK_THROWS_AS(ccd::validate_query(vertex_past_triangle({0, 0, 1}, {0, 0, -1}), negative), std::invalid_argument);
}

TEST_CASE("exact reference on rational text coordinates", "[ccd][reference]") {
  // Vertex from (1/3, 1/3, 1) to (1/3, 1/3, -1) through the unit triangle: 1/3 is not a double, the reference is exact.
  std::array<std::array<std::array<std::string, 2>, 3>, 8> points;
  const std::array<std::array<const char*, 3>, 4> numerators{
      {{"1", "1", "1"}, {"0", "0", "0"}, {"1", "0", "0"}, {"0", "1", "0"}}};
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d) points[i][d] = {numerators[i % 4][d], i % 4 == 0 && d < 2 ? "3" : "1"};
  points[4][2] = {"-1", "1"};
  CHECK(ccd::exact_collision_reference(PairKind::VertexFace, points));
  points[0][0] = points[4][0] = {"2", "3"};  // x + y = 1: on the hypotenuse, still a hit
  CHECK(ccd::exact_collision_reference(PairKind::VertexFace, points));
  points[0][0] = points[4][0] = {"200000000000000000000000000001", "300000000000000000000000000000"};  // just outside
  CHECK_FALSE(ccd::exact_collision_reference(PairKind::VertexFace, points));
  points[0][0][1] = "0";
  CHECK_THROWS_AS(ccd::exact_collision_reference(PairKind::VertexFace, points), std::invalid_argument);
}

TEST_CASE("contact parameters and normal do not depend on the scale", "[ccd][vertex-face][edge-edge]") {
  const auto vertex_face = vertex_past_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1});
  const auto edge_edge = edge_past_x_axis({Vector3d(0.5, -1, 1), Vector3d(0.5, 1, 1)},
                                          {Vector3d(0.5, -1, -1), Vector3d(0.5, 1, -1)});
  for (const ccd::CcdQuery& query : {vertex_face, edge_edge}) {
    const ccd::CcdResult unit = ccd::continuous_collision(query);
    REQUIRE(unit.hit);
    for (const double factor : {0x1p-900, 0x1p-300, 0x1p260, 0x1p300, 0x1p900}) {  // 1e-271 .. 1e271
      INFO("kind " << static_cast<int>(query.kind) << ", scale " << factor);
      const ccd::CcdResult result = ccd::continuous_collision(scaled(query, factor));
      CHECK(result.hit);
      CHECK(result.parameters[0] == Approx(unit.parameters[0]));
      CHECK(result.parameters[1] == Approx(unit.parameters[1]));
      CHECK(result.normal.isApprox(unit.normal));
    }
  }
}

TEST_CASE("with a NaN, infinite or negative thickness no filter culls and the CCD reports a conservative hit",
          "[ccd][filters][bad-input]") {
  const auto far_apart = vertex_past_triangle({5, 5, 5}, {5, 5, 6});  // every filter culls it at thickness 0
  REQUIRE(ccd::combined_filters_cull(far_apart, ccd::CcdSettings{}));
  for (const double thickness : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.0}) {
    INFO("thickness " << thickness);
    const ccd::CcdSettings settings{thickness};
    CHECK_FALSE(ccd::nonpenetration_filter_culls(far_apart, settings));
    CHECK_FALSE(ccd::projection_filter_culls(far_apart, settings));
    CHECK_FALSE(ccd::combined_filters_cull(far_apart, settings));
    const ccd::CcdResult result = ccd::continuous_collision(far_apart, settings);
    CHECK(result.hit);
    CHECK(result.state == ccd::CcdState::ConservativeHit);
  }
}
