// AABB and bounding sphere: every point inside, Welzl never larger than the naive sphere, hand-made exact cases.
#include <catch2/catch.hpp>

#include <cmath>

#include "clothcd/geometry/simple_bounds.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "geometry/geometry_test_helpers.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

Vertices rows(std::initializer_list<Eigen::RowVector3d> list) {
  Vertices v(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const auto& r : list) v.row(i++) = r;
  return v;
}

void check_sphere_bounds(const Vertices& points) {
  const Sphere s = compute_bounding_sphere(points);
  const Sphere naive = compute_bounding_sphere_naive(points);
  REQUIRE(s.radius >= 0);
  for (Eigen::Index i = 0; i < points.rows(); ++i) CHECK(s.contains(points.row(i).transpose()));
  // The minimal sphere can never be larger than any other bounding sphere.
  CHECK(s.radius <= naive.radius * (1 + 1e-9) + 1e-12);
}

}  // namespace

TEST_CASE("AABB of points and of an index subset", "[geometry][aabb]") {
  const Vertices v = rows({{1, 2, 3}, {-1, 5, 0}, {4, -2, 1}});
  const Aabb all = compute_aabb(v);
  CHECK(all.min == Eigen::Vector3d(-1, -2, 0));
  CHECK(all.max == Eigen::Vector3d(4, 5, 3));
  const Aabb some = compute_aabb(v, {0, 2});
  CHECK(some.min == Eigen::Vector3d(1, -2, 1));
  CHECK(some.max == Eigen::Vector3d(4, 2, 3));
  CHECK(compute_aabb(Vertices(0, 3)).volume() == 0.0);
}

TEST_CASE("Welzl sphere: hand-made exact cases", "[geometry][sphere]") {
  // Two points: the ball over the segment.
  Sphere s = compute_bounding_sphere(rows({{0, 0, 0}, {2, 0, 0}}));
  CHECK(s.radius == Approx(1.0));
  CHECK(s.center.isApprox(Eigen::Vector3d(1, 0, 0)));
  // Equilateral triangle of side 1: the circumradius 1/sqrt(3); the centroid is the centre.
  s = compute_bounding_sphere(rows({{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}}));
  CHECK(s.radius == Approx(1 / std::sqrt(3.0)));
  // Obtuse triangle: the longest side's ball, not the (larger) circumscribed ball.
  s = compute_bounding_sphere(rows({{-1, 0, 0}, {1, 0, 0}, {0, 0.1, 0}}));
  CHECK(s.radius == Approx(1.0));
  // Regular tetrahedron of edge sqrt(8) (alternate cube corners): circumradius sqrt(3).
  s = compute_bounding_sphere(rows({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}));
  CHECK(s.radius == Approx(std::sqrt(3.0)));
  CHECK(s.center.norm() < 1e-12);
  // Cube corners plus its centre: the centre is not a support point.
  s = compute_bounding_sphere(rows({{0, 0, 0}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {1, -1, -1}, {-1, 1, 1}, {-1, 1, -1},
                                    {-1, -1, 1}, {-1, -1, -1}}));
  CHECK(s.radius == Approx(std::sqrt(3.0)));
}

TEST_CASE("Welzl sphere bounds random and degenerate point sets", "[geometry][sphere]") {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) check_sphere_bounds(test::random_soup(200, seed, 3.0).vertices);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Vertices coplanar(300, 3), collinear(300, 3), duplicated(300, 3);
  for (int i = 0; i < 300; ++i) {
    coplanar.row(i) << u(random), u(random), 0.25;
    const double t = u(random);
    collinear.row(i) << 1 + t, 2 - 2 * t, 0.5 * t;
    duplicated.row(i) << (i % 3 == 0 ? 1.0 : -1.0), 0.5, (i % 2 == 0 ? 2.0 : 0.0);
  }
  check_sphere_bounds(coplanar);
  check_sphere_bounds(collinear);
  check_sphere_bounds(duplicated);
  const Sphere single = compute_bounding_sphere(rows({{3, 4, 5}, {3, 4, 5}}));
  CHECK(single.radius == 0.0);
  CHECK(single.center == Eigen::Vector3d(3, 4, 5));
  CHECK(compute_bounding_sphere(Vertices(0, 3)).radius < 0);
}

TEST_CASE("Welzl sphere bounds a real model and beats the naive sphere", "[geometry][sphere][models]") {
  const TriangleMesh cat = test::load_model("cat");
  check_sphere_bounds(cat.vertices);
  CHECK(compute_bounding_sphere(cat.vertices).radius < compute_bounding_sphere_naive(cat.vertices).radius);
}

TEST_CASE("Both spheres give the same ball at any scale", "[geometry][sphere]") {
  const TriangleMesh unit = make_uv_sphere(1.0, 8, 4);
  const Sphere welzl = compute_bounding_sphere(unit.vertices), naive = compute_bounding_sphere_naive(unit.vertices);
  for (const double factor : {0x1p-900, 0x1p-300, 0x1p300, 0x1p900}) {
    INFO("scale " << factor);
    const Vertices scaled = unit.vertices * factor;
    CHECK(compute_bounding_sphere(scaled).radius / factor == Approx(welzl.radius));
    CHECK(compute_bounding_sphere_naive(scaled).radius / factor == Approx(naive.radius));
  }
}
