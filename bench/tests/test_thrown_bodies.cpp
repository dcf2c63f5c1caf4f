// The scale benchmark's generated steps: the same bits from the same seed, the bodies the spec asks for, large motion,
// and clear errors on parameters out of range.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <stdexcept>

#include "clothcd/mesh/mesh_generators.hpp"
#include "thrown_bodies.hpp"

using clothcd::bench::make_thrown_bodies;
using clothcd::bench::ThrownBodiesSpec;

TEST_CASE("thrown bodies: the same seed gives the same bits, another seed another scene") {
  const ThrownBodiesSpec spec{"t", 6, 8, 1.0, 7};
  const auto a = make_thrown_bodies(spec), b = make_thrown_bodies(spec);
  CHECK(a.start.vertices == b.start.vertices);
  CHECK(a.start.faces == b.start.faces);
  CHECK(a.end == b.end);
  ThrownBodiesSpec other = spec;
  other.seed = 8;
  const auto c = make_thrown_bodies(other);
  REQUIRE(c.start.vertices.rows() == a.start.vertices.rows());
  CHECK(c.start.faces == a.start.faces);
  CHECK(c.start.vertices != a.start.vertices);
  CHECK(c.end != a.end);
}

TEST_CASE("thrown bodies: spheres, sheets and fish in turn, one mesh, every body moving far") {
  const int resolution = 8;
  const auto step = make_thrown_bodies({"t", 4, resolution, 3.0, 3});
  const clothcd::TriangleMesh sphere = clothcd::make_uv_sphere(1.0, resolution, resolution / 2);
  const clothcd::TriangleMesh sheet = clothcd::make_grid(resolution, resolution);
  const clothcd::TriangleMesh fish = clothcd::make_fish(resolution, 2 * resolution);
  CHECK(step.start.face_count() == 2 * sphere.face_count() + sheet.face_count() + fish.face_count());
  CHECK(step.start.vertex_count() == 2 * sphere.vertex_count() + sheet.vertex_count() + fish.vertex_count());
  CHECK(step.end.rows() == step.start.vertex_count());
  CHECK(step.start.faces.minCoeff() == 0);
  CHECK(step.start.faces.maxCoeff() == step.start.vertex_count() - 1);
  CHECK(step.start.vertices.allFinite());
  CHECK(step.end.allFinite());
  // The second body (the sheet) is rigid: its edge lengths are the same at both ends of the step.
  const Eigen::Index first = sphere.vertex_count();
  for (Eigen::Index f = 0; f < sheet.face_count(); ++f) {
    const int a = sheet.faces(f, 0) + static_cast<int>(first), b = sheet.faces(f, 1) + static_cast<int>(first);
    CHECK((step.start.vertices.row(a) - step.start.vertices.row(b)).norm() ==
          Approx((step.end.row(a) - step.end.row(b)).norm()).epsilon(1e-12));
  }
  // Large motion (at least 0.7 x 3 cells of 1.5 units, less half a radian of turn): every vertex travels more than
  // two body sizes.
  CHECK((step.end - step.start.vertices).rowwise().norm().minCoeff() > 2.0);
}

TEST_CASE("thrown bodies: parameters out of range are refused") {
  CHECK_THROWS_AS(make_thrown_bodies({"t", 0, 8, 1.0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(make_thrown_bodies({"t", 4, 3, 1.0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(make_thrown_bodies({"t", 4, 8, 0.0, 1}), std::invalid_argument);
}
