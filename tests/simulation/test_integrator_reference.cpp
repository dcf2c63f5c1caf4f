// The implicit integrator's matrix-free CG against a dense reference: the backward-Euler system written out from the
// spring forces and their Jacobians (Baraff and Witkin 1998, eqs. 6-7, the transverse stiffness dropped for compressed
// springs as the integrator documents) and solved directly.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/simulation/cloth_model.hpp"
#include "clothcd/simulation/implicit_integrator.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

using namespace clothcd;
using namespace clothcd::simulation;

namespace {

double stiffness(const ClothSettings& s, SpringKind kind) {
  if (kind == SpringKind::Structural) return s.structural_stiffness;
  return kind == SpringKind::Shear ? s.shear_stiffness : s.bending_stiffness;
}

// End-of-step velocities from the dense system (M - h dF/dv - h^2 dF/dx) dv = h (F + h dF/dx v0).
Vertices reference_velocities(const ClothModel& model, const ClothState& state, double h) {
  const ClothSettings& s = model.settings;
  const int n = model.vertex_count();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) {
    const double m = model.masses[i];
    const Eigen::Vector3d v = state.velocities.row(i).transpose();
    a.block<3, 3>(3 * i, 3 * i) += m * (1.0 + h * s.air_damping) * Eigen::Matrix3d::Identity();  // M - h dF/dv (air)
    b.segment<3>(3 * i) += h * (m * s.gravity - s.air_damping * m * v);
  }
  for (const Spring& spring : model.springs) {
    const Eigen::Vector3d d = (state.positions.row(spring.a) - state.positions.row(spring.b)).transpose();
    const double length = d.norm();
    const Eigen::Vector3d u = d / length;
    const Eigen::Matrix3d uu = u * u.transpose();
    const double k = stiffness(s, spring.kind);
    const double transverse = std::max(0.0, 1.0 - spring.rest_length / length);
    const Eigen::Matrix3d stiff = k * (uu + transverse * (Eigen::Matrix3d::Identity() - uu));  // -dF_a/dx_a
    const Eigen::Matrix3d damp = s.spring_damping * uu;                                        // -dF_a/dv_a
    const Eigen::Vector3d dv = (state.velocities.row(spring.a) - state.velocities.row(spring.b)).transpose();
    const Eigen::Vector3d force = -k * (length - spring.rest_length) * u - s.spring_damping * dv.dot(u) * u;
    const Eigen::Vector3d right = h * force - h * h * stiff * dv;
    const Eigen::Matrix3d block = h * damp + h * h * stiff;
    const int pa = 3 * spring.a, pb = 3 * spring.b;
    a.block<3, 3>(pa, pa) += block;
    a.block<3, 3>(pb, pb) += block;
    a.block<3, 3>(pa, pb) -= block;
    a.block<3, 3>(pb, pa) -= block;
    b.segment<3>(pa) += right;
    b.segment<3>(pb) -= right;
  }
  for (int i = 0; i < n; ++i) {
    if (!model.pinned[i]) continue;  // a pinned vertex keeps dv = 0: its rows and columns become the identity
    a.middleRows(3 * i, 3).setZero();
    a.middleCols(3 * i, 3).setZero();
    a.block<3, 3>(3 * i, 3 * i).setIdentity();
    b.segment<3>(3 * i).setZero();
  }
  const Eigen::VectorXd dv = a.ldlt().solve(b);
  Vertices v = state.velocities;
  for (int i = 0; i < n; ++i) {
    if (model.pinned[i]) v.row(i).setZero();
    else v.row(i) += dv.segment<3>(3 * i).transpose();
  }
  return v;
}

}  // namespace

TEST_CASE("the matrix-free CG solve equals a dense direct solve of the backward-Euler system",
          "[simulation][integrator]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> jitter(0.0, 0.03);
  ClothSettings settings;
  settings.spring_damping = 2.0;
  const ClothModel model = build_cloth_model(make_grid(6, 6, 1.0, 1.0), settings, {0, 5});
  ClothState state = rest_state(model);
  // Crumpled: some springs stretched, some compressed (their transverse term dropped); random velocities.
  for (Eigen::Index i = 0; i < state.positions.size(); ++i) {
    state.positions.data()[i] += jitter(rng);
    state.velocities.data()[i] = 20.0 * jitter(rng);
  }
  ImplicitIntegrator integrator(IntegratorSettings{1000, 1e-13});
  for (const double h : {0.001, 0.01, 0.05}) {
    INFO("h = " << h);
    Vertices v;
    const IntegratorResult result = integrator.predict_velocities(model, state, h, v);
    CHECK(result.relative_residual <= 1e-13);
    const Vertices expected = reference_velocities(model, state, h);
    CHECK((v - expected).cwiseAbs().maxCoeff() <= 1e-9 * expected.cwiseAbs().maxCoeff());
    CHECK(v.row(0).isZero());
    CHECK(v.row(5).isZero());
  }
}

TEST_CASE("the integrator's four-springs-at-a-time product gives the scalar product's result bit for bit",
          "[simulation][integrator]") {
  std::mt19937 rng(9);
  std::normal_distribution<double> jitter(0.0, 0.03);
  // 7 x 6 vertices: a spring count that is not a multiple of four, so the scalar tail runs too.
  const ClothModel model = build_cloth_model(make_grid(7, 6, 1.0, 0.7), ClothSettings{}, {3});
  REQUIRE(model.springs.size() % 4 != 0);
  ClothState state = rest_state(model);
  for (Eigen::Index i = 0; i < state.positions.size(); ++i) {
    state.positions.data()[i] += jitter(rng);
    state.velocities.data()[i] = 20.0 * jitter(rng);
  }
  state.positions.row(11) = state.positions.row(10);  // a spring of zero length (its block is skipped)
  Vertices baseline;
  {
    test::SimdLimit capped(SimdLevel::Baseline);
    ImplicitIntegrator(IntegratorSettings{50, 1e-12}).predict_velocities(model, state, 0.01, baseline);
  }
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    test::SimdLimit capped(level);
    Vertices wide;
    ImplicitIntegrator(IntegratorSettings{50, 1e-12}).predict_velocities(model, state, 0.01, wide);
    REQUIRE(wide.size() == baseline.size());
    CHECK(std::equal(wide.data(), wide.data() + wide.size(), baseline.data()));  // same bits, not just close
  }
}
