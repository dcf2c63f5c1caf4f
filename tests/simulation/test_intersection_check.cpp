// The independent frame check: hand-made triangle pairs, distances, and the grid against the brute force.
#include <catch2/catch.hpp>
#include <random>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/simulation/intersection_check.hpp"

using namespace clothcd;
using namespace clothcd::simulation;
using V = Eigen::Vector3d;

TEST_CASE("hand-made triangle pairs intersect or not", "[simulation][intersection]") {
  const Triangle flat{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  // Pierces the flat triangle through its interior.
  CHECK(triangles_intersect(flat, {V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.3, 0.3, 1)}));
  // Same shape lifted above: apart.
  CHECK_FALSE(triangles_intersect(flat, {V(0.2, 0.2, 0.1), V(0.2, 0.2, 1), V(0.3, 0.3, 1)}));
  // Touching at one corner counts.
  CHECK(triangles_intersect(flat, {V(1, 0, 0), V(2, 0, 1), V(2, 1, 1)}));
  // Coplanar and overlapping; coplanar and apart; one inside the other.
  CHECK(triangles_intersect(flat, {V(0.5, 0.5, 0), V(-0.5, 0.2, 0), V(0.2, -0.5, 0)}));
  CHECK_FALSE(triangles_intersect(flat, {V(1, 1, 0), V(2, 1, 0), V(1, 2, 0)}));
  CHECK(triangles_intersect(flat, {V(0.1, 0.1, 0), V(0.2, 0.1, 0), V(0.1, 0.2, 0)}));
  // Crossing the plane beside the triangle: no.
  CHECK_FALSE(triangles_intersect(flat, {V(2, 2, -1), V(2, 2, 1), V(3, 2, 1)}));
  // A degenerate (segment) triangle through the interior.
  CHECK(triangles_intersect(flat, {V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.2, 0.2, 0.5)}));
}

TEST_CASE("triangle distances of hand-made pairs", "[simulation][intersection]") {
  const Triangle flat{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  CHECK(triangle_distance(flat, {V(0.2, 0.2, 0.3), V(0.2, 0.2, 1), V(0.3, 0.3, 1)}) == Approx(0.3));
  CHECK(triangle_distance(flat, {V(2, 0, 0), V(3, 0, 0), V(2, 1, 0)}) == Approx(1.0));
  // Edge over edge: the skew segments (0.5, -1, 1)-(0.5, 1, 1) and the flat triangle's x axis edge.
  CHECK(triangle_distance(flat, {V(0.5, -1, 1), V(0.5, 1, 1), V(0.5, 0, 3)}) == Approx(1.0));
  CHECK(triangle_distance(flat, {V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.3, 0.3, 1)}) == 0.0);
}

TEST_CASE("adjacent cloth triangles do not count, a fold through the cloth does", "[simulation][intersection]") {
  TriangleMesh grid = make_grid(6, 6, 1.0, 1.0);
  IntersectionReport flat = check_frame(grid.faces, grid.vertices, {});
  CHECK(flat.intersecting_pairs() == 0);
  CHECK(std::isinf(flat.min_cloth_obstacle_distance));
  // Push one vertex far down through a box below: cloth-obstacle intersections appear.
  TriangleMesh box = make_box(V(0.5, 0.1, 0.5));
  box.vertices.col(1).array() -= 0.2;
  CHECK(check_frame(grid.faces, grid.vertices, {box}).intersecting_pairs() == 0);
  CHECK(std::isinf(check_frame(grid.faces, grid.vertices, {box}).min_cloth_obstacle_distance));  // beyond the margin
  IntersectionCheckSettings wide;
  wide.distance_margin = 0.2;
  CHECK(check_frame(grid.faces, grid.vertices, {box}, wide).min_cloth_obstacle_distance == Approx(0.1));
  grid.vertices(14, 1) = -0.25;
  const IntersectionReport poked = check_frame(grid.faces, grid.vertices, {box});
  CHECK(poked.cloth_obstacle_pairs > 0);
  CHECK(poked.min_cloth_obstacle_distance == 0.0);
}

TEST_CASE("the grid check equals the brute force on random crumpled cloths", "[simulation][intersection]") {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.12, 0.12);
  TriangleMesh sphere = make_uv_sphere(0.2, 12, 6);
  long total = 0;
  for (int trial = 0; trial < 8; ++trial) {
    TriangleMesh cloth = make_grid(10, 10, 1.0, 1.0);
    for (Eigen::Index i = 0; i < cloth.vertices.rows(); ++i) {
      for (int k = 0; k < 3; ++k) cloth.vertices(i, k) += jitter(rng) * (trial % 2 ? 1.0 : 0.3);
    }
    IntersectionCheckSettings settings;
    settings.cell_size = trial < 4 ? 0.0 : 0.05 + 0.1 * trial;
    const IntersectionReport grid = check_frame(cloth.faces, cloth.vertices, {sphere}, settings);
    const IntersectionReport brute = check_frame_brute_force(cloth.faces, cloth.vertices, {sphere}, settings);
    CHECK(grid.cloth_cloth_pairs == brute.cloth_cloth_pairs);
    CHECK(grid.cloth_obstacle_pairs == brute.cloth_obstacle_pairs);
    CHECK(grid.min_cloth_obstacle_distance == brute.min_cloth_obstacle_distance);
    total += brute.intersecting_pairs();
  }
  CHECK(total > 0);  // the inputs do exercise intersections
}

TEST_CASE("a tiny cloth across a huge obstacle is checked in the cloth's cells only", "[simulation][intersection]") {
  // A 1 cm cloth through a 10 m box: the grid's cells are 5 mm, so the box alone would cover about 10^10 of them.
  TriangleMesh cloth = make_grid(5, 5, 0.01, 0.01);
  cloth.vertices.col(1).array() += 10.0;  // the cloth at the top face of the box (half extents 10)
  cloth.vertices(12, 1) -= 0.004;        // its middle vertex pokes through it
  const TriangleMesh box = make_box(V(10, 10, 10));
  const IntersectionReport grid = check_frame(cloth.faces, cloth.vertices, {box});
  const IntersectionReport brute = check_frame_brute_force(cloth.faces, cloth.vertices, {box});
  CHECK(grid.cloth_obstacle_pairs == brute.cloth_obstacle_pairs);
  CHECK(grid.cloth_obstacle_pairs > 0);
  CHECK(grid.min_cloth_obstacle_distance == brute.min_cloth_obstacle_distance);
}

TEST_CASE("the frame check refuses bad obstacles and indices", "[simulation][intersection][bad-input]") {
  const TriangleMesh cloth = make_grid(4, 4, 1.0, 1.0);
  TriangleMesh box = make_box();
  box.vertices(2, 0) = std::nan("");
  CHECK_THROWS_WITH(check_frame(cloth.faces, cloth.vertices, {box}), Catch::Contains("obstacle 1") && Catch::Contains("NaN"));
  box = make_box();
  box.faces(3, 1) = 8;
  CHECK_THROWS_WITH(check_frame(cloth.faces, cloth.vertices, {box}), Catch::Contains("obstacle 1") && Catch::Contains("0..7"));
  Faces faces = cloth.faces;
  faces(0, 0) = -1;
  CHECK_THROWS_WITH(check_frame(faces, cloth.vertices, {}), Catch::Contains("the cloth"));
}
