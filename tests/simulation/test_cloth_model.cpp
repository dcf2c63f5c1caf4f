// The mass-spring cloth model and the implicit integrator: spring counts on a grid, masses, bad settings, free fall,
// stability at a large step.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/simulation/cloth_model.hpp"
#include "clothcd/simulation/implicit_integrator.hpp"

using namespace clothcd;
using namespace clothcd::simulation;

TEST_CASE("a grid cloth gets structural, shear and bending springs of a quad grid", "[simulation][cloth]") {
  const int n = 6;
  const ClothModel model = build_cloth_model(make_grid(n, n, 1.0, 1.0));
  const std::vector<int> counts = count_springs(model);
  // n x n vertices: 2 n (n-1) weave edges, two diagonals per quad, 2 n (n-2) skip-one springs.
  CHECK(counts[static_cast<int>(SpringKind::Structural)] == 2 * n * (n - 1));
  CHECK(counts[static_cast<int>(SpringKind::Shear)] == 2 * (n - 1) * (n - 1));
  CHECK(counts[static_cast<int>(SpringKind::Bending)] == 2 * n * (n - 2));
  const double h = 1.0 / (n - 1);
  for (const Spring& s : model.springs) {
    const double expected = s.kind == SpringKind::Structural ? h : s.kind == SpringKind::Shear ? std::sqrt(2.0) * h : 2 * h;
    CHECK(s.rest_length == Approx(expected));
    CHECK(s.a < s.b);
  }
}

TEST_CASE("masses add up to density times area", "[simulation][cloth]") {
  ClothSettings settings;
  settings.density = 0.3;
  const ClothModel model = build_cloth_model(make_grid(9, 5, 2.0, 1.0), settings, {0, 8});
  double total = 0;
  for (const double m : model.masses) total += m;
  CHECK(total == Approx(0.3 * 2.0));
  CHECK(model.inverse_mass(0) == 0.0);
  CHECK(model.inverse_mass(1) > 0.0);
}

TEST_CASE("bad cloth input is rejected with a clear message", "[simulation][cloth][bad-input]") {
  TriangleMesh grid = make_grid(4, 4);
  CHECK_THROWS_WITH(build_cloth_model(grid, {}, {16}), Catch::Contains("pinned vertex 16"));
  ClothSettings negative;
  negative.structural_stiffness = -1;
  CHECK_THROWS_WITH(build_cloth_model(grid, negative), Catch::Contains("structural_stiffness"));
  grid.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS(build_cloth_model(grid));
}

TEST_CASE("an unconstrained cloth falls freely under gravity", "[simulation][integrator]") {
  ClothSettings settings;
  settings.air_damping = 0;
  const ClothModel model = build_cloth_model(make_grid(5, 5), settings);
  const ClothState state = rest_state(model);
  ImplicitIntegrator integrator;
  Vertices v;
  integrator.predict_velocities(model, state, 0.01, v);
  // Springs at rest exert nothing: every vertex gains g dt.
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    CHECK(v(i, 0) == Approx(0.0).margin(1e-9));
    CHECK(v(i, 1) == Approx(-9.81 * 0.01).epsilon(1e-6));
  }
}

TEST_CASE("a pinned cloth hangs without blowing up at a large step", "[simulation][integrator]") {
  // Cloth C's stiffness at 20 ms steps: h sqrt(k/m) >> 1, where explicit Euler would explode.
  TriangleMesh grid = make_grid(20, 20, 1.0, 1.0);
  const ClothModel model = build_cloth_model(grid, {}, {0, 19});
  ClothState state = rest_state(model);
  ImplicitIntegrator integrator;
  Vertices v;
  for (int step = 0; step < 100; ++step) {
    integrator.predict_velocities(model, state, 0.02, v);
    state.velocities = v;
    state.positions += 0.02 * v;
  }
  REQUIRE(state.positions.allFinite());
  CHECK(state.positions.row(0).isApprox(grid.vertices.row(0)));
  CHECK(state.positions.col(1).minCoeff() > -2.0);  // hangs about 1 m down, stretched a little
  CHECK(state.positions.col(1).minCoeff() < -0.5);  // and it did fall
  CHECK(state.velocities.cwiseAbs().maxCoeff() < 5.0);
}

TEST_CASE("a time step that overflows the implicit system is an error, not a frozen cloth", "[simulation][integrator][bad-input]") {
  const ClothModel model = build_cloth_model(make_grid(5, 5));
  const ClothState state = rest_state(model);
  ImplicitIntegrator integrator;
  Vertices v;
  CHECK_THROWS_WITH(integrator.predict_velocities(model, state, 1e300, v), Catch::Contains("time step"));
  CHECK_NOTHROW(integrator.predict_velocities(model, state, 1.0, v));
  for (const double dt : {-1.0, 0.0, std::numeric_limits<double>::quiet_NaN()})
    CHECK_THROWS_AS(integrator.predict_velocities(model, state, dt, v), std::invalid_argument);
  ClothState short_state = state;
  short_state.velocities.conservativeResize(3, 3);
  CHECK_THROWS_WITH(integrator.predict_velocities(model, short_state, 0.01, v), Catch::Contains("3 velocities"));
}
