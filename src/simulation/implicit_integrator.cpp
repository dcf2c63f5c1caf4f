// Linearised backward Euler for mass-spring systems: Baraff and Witkin, "Large Steps in Cloth Simulation", SIGGRAPH 1998,
// eq. (6)-(7), with the usual definiteness fix of Choi and Ko 2002: the transverse term k (1 - L / l) (I - n n^T) of a
// spring's stiffness is dropped when the spring is compressed, so the system matrix stays symmetric positive definite
// and plain preconditioned CG applies. Pinned vertices are handled by filtering (Baraff-Witkin section 5.3).
#include "clothcd/simulation/implicit_integrator.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace

ImplicitIntegrator::ImplicitIntegrator(const IntegratorSettings& settings) : settings_(settings) {
  if (settings.max_cg_iterations < 1 || !(settings.cg_tolerance > 0.0 && settings.cg_tolerance < 1.0))
    throw std::invalid_argument("integrator: need max_cg_iterations >= 1 and 0 < cg_tolerance < 1");
}

void ImplicitIntegrator::multiply(const ClothModel& model, const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  out = mass_diagonal_.cwiseProduct(p);
  const double* in = p.data();
  double* sum = out.data();
  for (const SpringBlock& b : blocks_) {
    // S q = alpha (n . q) n + beta q with the operations of the Eigen expression alpha * n.dot(q) * n + beta * q, in its
    // order: n . q = (n0 q0 + n1 q1) + n2 q2, then per axis (alpha (n . q)) n_c + beta q_c. The block is read into
    // locals first, as the stores into `sum` could otherwise alias it.
    const double n0 = b.n[0], n1 = b.n[1], n2 = b.n[2], beta = b.beta;
    const int a3 = b.a3, b3 = b.b3;
    const double q0 = in[a3] - in[b3], q1 = in[a3 + 1] - in[b3 + 1], q2 = in[a3 + 2] - in[b3 + 2];
    const double scale = b.alpha * ((n0 * q0 + n1 * q1) + n2 * q2);
    const double s0 = scale * n0 + beta * q0, s1 = scale * n1 + beta * q1, s2 = scale * n2 + beta * q2;
    sum[a3] += s0;
    sum[a3 + 1] += s1;
    sum[a3 + 2] += s2;
    sum[b3] -= s0;
    sum[b3 + 1] -= s1;
    sum[b3 + 2] -= s2;
  }
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

  blocks_.resize(model.springs.size());
  for (size_t s = 0; s < model.springs.size(); ++s) {
    const Spring& spring = model.springs[s];
    const Eigen::Vector3d d = x.segment<3>(3 * spring.a) - x.segment<3>(3 * spring.b);
    const double length = d.norm();
    const double k = stiffness_of(cs, spring.kind);
    SpringBlock& b = blocks_[s];
    b.a3 = 3 * spring.a;
    b.b3 = 3 * spring.b;
    if (length <= 1e-12) {
      b.n = Eigen::Vector3d::UnitX();
      b.alpha = b.beta = 0.0;
      continue;
    }
    b.n = d / length;
    const double transverse = std::max(0.0, 1.0 - spring.rest_length / length);
    const Eigen::Vector3d dv = v.segment<3>(3 * spring.a) - v.segment<3>(3 * spring.b);
    // Force on a: elastic -k (l - L) n, damping -kd (dv . n) n.
    const Eigen::Vector3d force = (-k * (length - spring.rest_length) - cs.spring_damping * dv.dot(b.n)) * b.n;
    // h^2 (-dF/dx) v0 with -dF/dx = k [n n^T + transverse (I - n n^T)].
    const Eigen::Vector3d kv = k * ((1.0 - transverse) * dv.dot(b.n) * b.n + transverse * dv);
    const Eigen::Vector3d contribution = h * force - h * h * kv;
    rhs_.segment<3>(3 * spring.a) += contribution;
    rhs_.segment<3>(3 * spring.b) -= contribution;
    b.beta = h * h * k * transverse;
    b.alpha = h * h * k + h * cs.spring_damping - b.beta;
    const Eigen::Vector3d block_diagonal = b.alpha * b.n.cwiseAbs2() + Eigen::Vector3d::Constant(b.beta);
    diagonal_.segment<3>(3 * spring.a) += block_diagonal;
    diagonal_.segment<3>(3 * spring.b) += block_diagonal;
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
    dv_ += step * p_;
    r_ -= step * ap_;
    z_ = r_.cwiseQuotient(diagonal_);
    const double rz_next = r_.dot(z_);
    p_ = z_ + (rz_next / rz) * p_;
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
