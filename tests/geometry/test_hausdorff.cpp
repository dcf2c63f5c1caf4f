// Sampled Hausdorff distance on shapes with a known answer.
#include <catch2/catch.hpp>

#include "clothcd/geometry/hausdorff.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

TEST_CASE("Hausdorff distance of identical and shifted surfaces", "[geometry][hausdorff]") {
  const TriangleMesh grid = make_grid(11, 11);
  HausdorffSettings s;
  s.samples = 5000;
  CHECK(hausdorff_distance(grid, grid, s) < 1e-12);
  // Lifted by 0.3 along the normal: every sample is exactly 0.3 from the other plane.
  TriangleMesh lifted = grid;
  lifted.vertices.col(1).array() += 0.3;
  const HausdorffResult r = measure_hausdorff(grid, lifted, s);
  CHECK(r.max == Approx(0.3));
  CHECK(r.mean == Approx(0.3));
}

TEST_CASE("Hausdorff distance is two-sided", "[geometry][hausdorff]") {
  // The unit square against its left half: every point of the half lies on the square (one side 0), while the far
  // edge of the square is 0.5 from the half (other side 0.5).
  const TriangleMesh square = make_grid(11, 11, 1.0, 1.0);
  TriangleMesh half = make_grid(6, 11, 0.5, 1.0);
  half.vertices.col(0).array() -= 0.25;
  HausdorffSettings s;
  s.samples = 20000;
  const HausdorffResult r = measure_hausdorff(half, square, s);
  CHECK(r.a_to_b < 1e-12);
  CHECK(r.b_to_a == Approx(0.5));
  CHECK(r.max == Approx(0.5));
  CHECK_THROWS_AS(measure_hausdorff(TriangleMesh{}, square), std::invalid_argument);
  TriangleMesh bad = square;
  bad.faces(0, 1) = static_cast<int>(bad.vertex_count());
  CHECK_THROWS_WITH(measure_hausdorff(square, bad), Catch::Contains("out of range"));
  bad = square;
  bad.vertices(0, 2) = std::nan("");
  CHECK_THROWS_WITH(measure_hausdorff(bad, square), Catch::Contains("NaN"));
}
