// Linearised backward Euler for mass-spring systems: Baraff and Witkin, "Large Steps in Cloth Simulation", SIGGRAPH 1998,
// eq. (6)-(7), with the usual definiteness fix of Choi and Ko 2002: the transverse term k (1 - L / l) (I - n n^T) of a
// spring's stiffness is dropped when the spring is compressed, so the system matrix stays symmetric positive definite
// and plain preconditioned CG applies. Pinned vertices are handled by filtering (Baraff-Witkin section 5.3).
#include "clothcd/simulation/implicit_integrator.hpp"

#include "clothcd/simd_level.hpp"
#include "support/simd.hpp"

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

#if defined(CLOTHCD_SIMD_X86)
using simd::d4::Doubles;
using simd::d4::load;
using simd::d4::load3;
using simd::d4::splat;
using simd::d4::store;

// Loads rows (x, y, z) of a stacked 3n vector at four offsets and returns them as the four x's, y's and z's.
CLOTHCD_SIMD_AVX2 void gather_rows(const double* stacked, const int* offsets, Doubles out[3]) {
  const Doubles rows[4] = {load3(stacked + offsets[0]), load3(stacked + offsets[1]), load3(stacked + offsets[2]),
                           load3(stacked + offsets[3])};
  simd::d4::transpose3(rows, out);
}

// multiply_springs for the springs [0, 4 floor(count / 4)), four at a time: the same operations in the same order on
// each spring (the library is built without contraction into fused multiply-adds), and the sums updated spring by
// spring in order, so the result is bit for bit the scalar one. Returns the number of springs done.
CLOTHCD_SIMD_AVX2 std::size_t multiply_springs_avx2(const double* n0, const double* n1, const double* n2,
                                                    const double* alpha, const double* beta, const int* a3s,
                                                    const int* b3s, std::size_t count, const double* in,
                                                    double* sum) {
  const std::size_t whole = count / 4 * 4;
  alignas(32) double s[3][4];
  for (std::size_t k = 0; k < whole; k += 4) {
    Doubles d[4], q[3];  // (q0, q1, q2, 0) of the four springs, then the four q0's, q1's and q2's
    for (int l = 0; l < 4; ++l) d[l] = load3(in + a3s[k + l]) - load3(in + b3s[k + l]);
    simd::d4::transpose3(d, q);
    const Doubles m[3] = {load(n0 + k), load(n1 + k), load(n2 + k)};
    const Doubles b = load(beta + k);
    const Doubles scale = load(alpha + k) * ((m[0] * q[0] + m[1] * q[1]) + m[2] * q[2]);
    for (int c = 0; c < 3; ++c) store(s[c], scale * m[c] + b * q[c]);
    for (int l = 0; l < 4; ++l) {
      const int a3 = a3s[k + l], b3 = b3s[k + l];
      sum[a3] += s[0][l];
      sum[a3 + 1] += s[1][l];
      sum[a3 + 2] += s[2][l];
      sum[b3] -= s[0][l];
      sum[b3 + 1] -= s[1][l];
      sum[b3 + 2] -= s[2][l];
    }
  }
  return whole;
}

// The CG's elementwise updates dv += step p, r -= step ap, z = r / diagonal on [0, 4 floor(n / 4)), four at a time, in
// one pass: the same operation per element as the Eigen expressions (so the same values); returns the count done.
CLOTHCD_SIMD_AVX2 Eigen::Index cg_step_avx2(double step, const double* p, const double* ap, const double* diagonal,
                                            double* dv, double* r, double* z, Eigen::Index n) {
  const Doubles s = splat(step);
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) {
    store(dv + i, load(dv + i) + s * load(p + i));
    const Doubles ri = load(r + i) - s * load(ap + i);
    store(r + i, ri);
    store(z + i, ri / load(diagonal + i));
  }
  return i;
}

// (a0 b0 + a1 b1) + a2 b2, the order of Eigen's 3-vector dot product and squared norm.
CLOTHCD_SIMD_AVX2 Doubles dot3(const Doubles a[3], const Doubles b[3]) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

// The per-spring linearisation of predict_velocities for springs [0, 4 floor(count / 4)), four at a time: the same
// operations in the same order as its scalar loop (the Eigen expressions there), blocks written per field, and rhs and
// diagonal updated spring by spring in order, so the result is bit for bit the scalar one. `rest` and `stiffness`
// hold each spring's rest length and k. Returns the number of springs done.
CLOTHCD_SIMD_AVX2 std::size_t linearise_springs_avx2(const double* x, const double* v, const double* rest,
                                                     const double* stiffness, double h, double damping,
                                                     std::size_t count, double* n0, double* n1, double* n2,
                                                     double* alpha, double* beta, const int* a3s, const int* b3s,
                                                     double* rhs, double* diagonal) {
  const std::size_t whole = count / 4 * 4;
  const Doubles zero = splat(0.0), one = splat(1.0), hv = splat(h);
  const Doubles hh = splat(h * h), hd = splat(h * damping), kd = splat(damping);
  const Doubles tiny = splat(1e-12);
  alignas(32) double contribution[3][4], block_diagonal[3][4];
  for (std::size_t s = 0; s < whole; s += 4) {
    Doubles xa[3], xb[3], va[3], vb[3], d[3], n[3], dv[3];
    gather_rows(x, a3s + s, xa);
    gather_rows(x, b3s + s, xb);
    for (int c = 0; c < 3; ++c) d[c] = xa[c] - xb[c];
    const Doubles length = simd::d4::sqrt(dot3(d, d));
    const auto ok = length > tiny;  // length > 1e-12 (false for NaN)
    for (int c = 0; c < 3; ++c) n[c] = d[c] / length;
    const Doubles r = load(rest + s), k = load(stiffness + s);
    const Doubles t = one - r / length;
    const Doubles transverse = simd::d4::select(zero < t, t, zero);  // std::max(0.0, t)
    gather_rows(v, a3s + s, va);
    gather_rows(v, b3s + s, vb);
    for (int c = 0; c < 3; ++c) dv[c] = va[c] - vb[c];
    const Doubles along = dot3(dv, n);
    const Doubles scale = -k * (length - r) - kd * along;
    const Doubles c1 = (one - transverse) * along;
    const Doubles b = hh * k * transverse;
    const Doubles a = (hh * k + hd) - b;
    for (int c = 0; c < 3; ++c) {
      const Doubles force = scale * n[c];
      const Doubles kv = k * (c1 * n[c] + transverse * dv[c]);
      store(contribution[c], hv * force - hh * kv);
      store(block_diagonal[c], a * (n[c] * n[c]) + b);
    }
    // Degenerate springs keep n = (1, 0, 0), alpha = beta = 0 and add nothing.
    store(n0 + s, simd::d4::select(ok, n[0], one));
    store(n1 + s, simd::d4::select(ok, n[1], zero));
    store(n2 + s, simd::d4::select(ok, n[2], zero));
    store(alpha + s, simd::d4::select(ok, a, zero));
    store(beta + s, simd::d4::select(ok, b, zero));
    const unsigned valid = simd::d4::bits(ok);
    for (int l = 0; l < 4; ++l) {
      if (((valid >> l) & 1u) == 0) continue;
      const int a3 = a3s[s + l], b3 = b3s[s + l];
      for (int c = 0; c < 3; ++c) rhs[a3 + c] += contribution[c][l];
      for (int c = 0; c < 3; ++c) rhs[b3 + c] -= contribution[c][l];
      for (int c = 0; c < 3; ++c) diagonal[a3 + c] += block_diagonal[c][l];
      for (int c = 0; c < 3; ++c) diagonal[b3 + c] += block_diagonal[c][l];
    }
  }
  return whole;
}

// The CG's new search direction p = z + c p on [0, 4 floor(n / 4)), four at a time; returns the count done.
CLOTHCD_SIMD_AVX2 Eigen::Index cg_direction_avx2(double c, const double* z, double* p, Eigen::Index n) {
  const Doubles cs = splat(c);
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) store(p + i, load(z + i) + cs * load(p + i));
  return i;
}
#endif

}  // namespace

ImplicitIntegrator::ImplicitIntegrator(const IntegratorSettings& settings) : settings_(settings) {
  if (settings.max_cg_iterations < 1 || !(settings.cg_tolerance > 0.0 && settings.cg_tolerance < 1.0))
    throw std::invalid_argument("integrator: need max_cg_iterations >= 1 and 0 < cg_tolerance < 1");
}

void ImplicitIntegrator::multiply(const ClothModel& model, const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  out = mass_diagonal_.cwiseProduct(p);
  const SpringBlocks& b = blocks_;
  const std::size_t count = b.alpha.size();
  std::size_t done = 0;
#if defined(CLOTHCD_SIMD_X86)
  if (simd_level() >= SimdLevel::Avx2) {
    done = multiply_springs_avx2(b.n0.data(), b.n1.data(), b.n2.data(), b.alpha.data(), b.beta.data(), b.a3.data(),
                                 b.b3.data(), count, p.data(), out.data());
  }
#endif
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
  std::size_t linearised = 0;
#if defined(CLOTHCD_SIMD_X86)
  if (simd_level() >= SimdLevel::Avx2) {
    linearised = linearise_springs_avx2(state.positions.data(), state.velocities.data(), blocks_.rest.data(),
                                        blocks_.stiffness.data(), h, cs.spring_damping, springs, blocks_.n0.data(),
                                        blocks_.n1.data(), blocks_.n2.data(), blocks_.alpha.data(),
                                        blocks_.beta.data(), blocks_.a3.data(), blocks_.b3.data(), rhs_.data(),
                                        diagonal_.data());
  }
#endif
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
    Eigen::Index done = 0;
#if defined(CLOTHCD_SIMD_X86)
    if (simd_level() >= SimdLevel::Avx2) {
      done = cg_step_avx2(step, p_.data(), ap_.data(), diagonal_.data(), dv_.data(), r_.data(), z_.data(), size);
    }
#endif
    const Eigen::Index rest = size - done;
    dv_.tail(rest) += step * p_.tail(rest);
    r_.tail(rest) -= step * ap_.tail(rest);
    z_.tail(rest) = r_.tail(rest).cwiseQuotient(diagonal_.tail(rest));
    const double rz_next = r_.dot(z_);
    const double c = rz_next / rz;
    done = 0;
#if defined(CLOTHCD_SIMD_X86)
    if (simd_level() >= SimdLevel::Avx2) done = cg_direction_avx2(c, z_.data(), p_.data(), size);
#endif
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
