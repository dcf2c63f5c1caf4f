// Linearised backward Euler for mass-spring systems: Baraff and Witkin, "Large Steps in Cloth Simulation", SIGGRAPH 1998,
// eq. (6)-(7), with the usual definiteness fix of Choi and Ko 2002: the transverse term k (1 - L / l) (I - n n^T) of a
// spring's stiffness is dropped when the spring is compressed, so the system matrix stays symmetric positive definite
// and plain preconditioned CG applies. Pinned vertices are handled by filtering (Baraff-Witkin section 5.3).
#include "clothcd/simulation/implicit_integrator.hpp"

#include "support/simd.hpp"
#include "support/simd_level.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

namespace clothcd::simulation {
namespace {

double stiffness_of(const ClothSettings& s, SpringKind kind) {
  switch (kind) {
    case SpringKind::Structural: return s.structural_stiffness;
    case SpringKind::Shear: return s.shear_stiffness;
    case SpringKind::Bending: return s.bending_stiffness;
  }
  return 0.0;
}

void filter_pinned(const ClothModel& model, Eigen::Ref<Eigen::VectorXd> v) {
  for (int i = 0; i < model.vertex_count(); ++i) {
    if (model.pinned[i]) v.segment<3>(3 * i).setZero();
  }
}

// Adds S_k (in_a - in_b) to sum_a and subtracts it from sum_b for springs k in [begin, end), in order. S q is evaluated
// with the operations of the Eigen expression alpha * n.dot(q) * n + beta * q, in its order: n . q = (n0 q0 + n1 q1) +
// n2 q2, then per axis (alpha (n . q)) n_c + beta q_c.
void multiply_springs(const double* n0, const double* n1, const double* n2, const double* alpha, const double* beta,
                      const int* a3s, const int* b3s, std::size_t begin, std::size_t end, const double* in,
                      double* sum) {
  for (std::size_t k = begin; k < end; ++k) {
    const int a3 = a3s[k], b3 = b3s[k];
    const double q0 = in[a3] - in[b3], q1 = in[a3 + 1] - in[b3 + 1], q2 = in[a3 + 2] - in[b3 + 2];
    const double scale = alpha[k] * ((n0[k] * q0 + n1[k] * q1) + n2[k] * q2);
    const double s0 = scale * n0[k] + beta[k] * q0, s1 = scale * n1[k] + beta[k] * q1,
                 s2 = scale * n2[k] + beta[k] * q2;
    sum[a3] += s0;
    sum[a3 + 1] += s1;
    sum[a3 + 2] += s2;
    sum[b3] -= s0;
    sum[b3 + 1] -= s1;
    sum[b3 + 2] -= s2;
  }
}

// The wide kernels: the springs and the conjugate-gradient updates on four double lanes.
#define CLOTHCD_SIMD_KERNEL "simulation/implicit_integrator_lanes.hpp"
#define CLOTHCD_SIMD_KERNEL_WIDE
#include "support/simd_versions.hpp"

}  // namespace

ImplicitIntegrator::ImplicitIntegrator(const IntegratorSettings& settings) : settings_(settings) {
  if (settings.max_cg_iterations < 1 || !(settings.cg_tolerance > 0.0 && settings.cg_tolerance < 1.0))
    throw std::invalid_argument("integrator: need max_cg_iterations >= 1 and 0 < cg_tolerance < 1");
}

void ImplicitIntegrator::multiply(const ClothModel& model, const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  out = mass_diagonal_.cwiseProduct(p);
  const SpringBlocks& b = blocks_;
  const std::size_t count = b.alpha.size();
  const std::size_t done = CLOTHCD_SIMD_DISPATCH_WIDE(
      simd_level(),
      multiply_springs_wide(b.n0.data(), b.n1.data(), b.n2.data(), b.alpha.data(), b.beta.data(), b.a3.data(),
                            b.b3.data(), count, p.data(), out.data()),
      std::size_t{0});
  multiply_springs(b.n0.data(), b.n1.data(), b.n2.data(), b.alpha.data(), b.beta.data(), b.a3.data(), b.b3.data(),
                   done, count, p.data(), out.data());
  filter_pinned(model, out);
}

IntegratorResult ImplicitIntegrator::predict_velocities(const ClothModel& model, const ClothState& state, double dt,
                                                        Vertices& velocities) {
  const ClothSettings& cs = model.settings;
  const int n = model.vertex_count();
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("implicit integration: the time step must be finite and > 0, got " + std::to_string(dt));
  if (state.positions.rows() != n || state.velocities.rows() != n)
    throw std::invalid_argument("implicit integration: the state has " + std::to_string(state.positions.rows()) +
                                " positions and " + std::to_string(state.velocities.rows()) + " velocities for " +
                                std::to_string(n) + " cloth vertices");
  const double h = dt;
  const Eigen::Map<const Eigen::VectorXd> x(state.positions.data(), 3 * n);
  const Eigen::Map<const Eigen::VectorXd> v(state.velocities.data(), 3 * n);

  mass_diagonal_.resize(3 * n);
  rhs_.resize(3 * n);
  for (int i = 0; i < n; ++i) {
    const double m = model.masses[i];
    mass_diagonal_.segment<3>(3 * i).setConstant(m * (1.0 + h * cs.air_damping));
    rhs_.segment<3>(3 * i) = h * m * (cs.gravity - cs.air_damping * v.segment<3>(3 * i));
  }
  diagonal_ = mass_diagonal_;

  const std::size_t springs = model.springs.size();
  for (std::vector<double>* field : {&blocks_.n0, &blocks_.n1, &blocks_.n2, &blocks_.alpha, &blocks_.beta,
                                     &blocks_.rest, &blocks_.stiffness}) {
    field->resize(springs);
  }
  blocks_.a3.resize(springs);
  blocks_.b3.resize(springs);
  for (size_t s = 0; s < springs; ++s) {
    const Spring& spring = model.springs[s];
    blocks_.a3[s] = 3 * spring.a;
    blocks_.b3[s] = 3 * spring.b;
    blocks_.rest[s] = spring.rest_length;
    blocks_.stiffness[s] = stiffness_of(cs, spring.kind);
  }
  const std::size_t linearised = CLOTHCD_SIMD_DISPATCH_WIDE(
      simd_level(),
      linearise_springs_wide(state.positions.data(), state.velocities.data(), blocks_.rest.data(),
                             blocks_.stiffness.data(), h, cs.spring_damping, springs, blocks_.n0.data(),
                             blocks_.n1.data(), blocks_.n2.data(), blocks_.alpha.data(), blocks_.beta.data(),
                             blocks_.a3.data(), blocks_.b3.data(), rhs_.data(), diagonal_.data()),
      std::size_t{0});
  for (size_t s = linearised; s < springs; ++s) {
    const Spring& spring = model.springs[s];
    const Eigen::Vector3d d = x.segment<3>(3 * spring.a) - x.segment<3>(3 * spring.b);
    const double length = d.norm();
    const double k = blocks_.stiffness[s];
    double alpha = 0.0, beta = 0.0;
    Eigen::Vector3d n = Eigen::Vector3d::UnitX();
    if (length > 1e-12) {
      n = d / length;
      const double transverse = std::max(0.0, 1.0 - spring.rest_length / length);
      const Eigen::Vector3d dv = v.segment<3>(3 * spring.a) - v.segment<3>(3 * spring.b);
      // Force on a: elastic -k (l - L) n, damping -kd (dv . n) n.
      const Eigen::Vector3d force = (-k * (length - spring.rest_length) - cs.spring_damping * dv.dot(n)) * n;
      // h^2 (-dF/dx) v0 with -dF/dx = k [n n^T + transverse (I - n n^T)].
      const Eigen::Vector3d kv = k * ((1.0 - transverse) * dv.dot(n) * n + transverse * dv);
      const Eigen::Vector3d contribution = h * force - h * h * kv;
      rhs_.segment<3>(3 * spring.a) += contribution;
      rhs_.segment<3>(3 * spring.b) -= contribution;
      beta = h * h * k * transverse;
      alpha = h * h * k + h * cs.spring_damping - beta;
      const Eigen::Vector3d block_diagonal = alpha * n.cwiseAbs2() + Eigen::Vector3d::Constant(beta);
      diagonal_.segment<3>(3 * spring.a) += block_diagonal;
      diagonal_.segment<3>(3 * spring.b) += block_diagonal;
    }
    blocks_.n0[s] = n[0];
    blocks_.n1[s] = n[1];
    blocks_.n2[s] = n[2];
    blocks_.alpha[s] = alpha;
    blocks_.beta[s] = beta;
  }
  filter_pinned(model, rhs_);
  if (!std::isfinite(rhs_.squaredNorm()) || !std::isfinite(diagonal_.sum())) {
    std::ostringstream message;
    message << "implicit integration: the linear system is not finite (time step " << h
            << " s too large for the cloth's stiffness and speeds?)";
    throw std::runtime_error(message.str());
  }

  dv_.setZero(3 * n);
  r_ = rhs_;
  z_ = r_.cwiseQuotient(diagonal_);
  p_ = z_;
  double rz = r_.dot(z_);
  const double rhs_norm = std::max(rhs_.norm(), 1e-300);
  IntegratorResult result;
  result.relative_residual = r_.norm() / rhs_norm;
  while (result.cg_iterations < settings_.max_cg_iterations && result.relative_residual > settings_.cg_tolerance) {
    multiply(model, p_, ap_);
    const double pap = p_.dot(ap_);
    if (!(pap > 0)) break;
    const double step = rz / pap;
    const Eigen::Index size = dv_.size();
    Eigen::Index done = CLOTHCD_SIMD_DISPATCH_WIDE(
        simd_level(), cg_step_wide(step, p_.data(), ap_.data(), diagonal_.data(), dv_.data(), r_.data(), z_.data(), size),
        Eigen::Index{0});
    const Eigen::Index rest = size - done;
    dv_.tail(rest) += step * p_.tail(rest);
    r_.tail(rest) -= step * ap_.tail(rest);
    z_.tail(rest) = r_.tail(rest).cwiseQuotient(diagonal_.tail(rest));
    const double rz_next = r_.dot(z_);
    const double c = rz_next / rz;
    done = CLOTHCD_SIMD_DISPATCH_WIDE(simd_level(), cg_direction_wide(c, z_.data(), p_.data(), size), Eigen::Index{0});
    p_.tail(size - done) = z_.tail(size - done) + c * p_.tail(size - done);
    rz = rz_next;
    ++result.cg_iterations;
    result.relative_residual = r_.norm() / rhs_norm;
  }

  velocities.resize(n, 3);
  Eigen::Map<Eigen::VectorXd> out(velocities.data(), 3 * n);
  out = v + dv_;
  filter_pinned(model, out);
  return result;
}

}  // namespace clothcd::simulation
