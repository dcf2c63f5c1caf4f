// The wide kernels of implicit_integrator.cpp (the springs' products and linearisation, the conjugate-gradient
// updates), written once on the vector layer (support/simd.hpp) and compiled there for AVX2 by
// support/simd_versions.hpp; each does a prefix of the work and the scalar code beside it there does the rest (all of
// it at the baseline). No include guard and no includes of its own, on purpose.

using lanes::Doubles;
using lanes::load;
using lanes::load3;
using lanes::splat;
using lanes::store;

// Loads rows (x, y, z) of a stacked 3n vector at four offsets and returns them as the four x's, y's and z's.
inline void gather_rows(const double* stacked, const int* offsets, Doubles out[3]) {
  const Doubles rows[4] = {load3(stacked + offsets[0]), load3(stacked + offsets[1]), load3(stacked + offsets[2]),
                           load3(stacked + offsets[3])};
  lanes::transpose3(rows, out);
}

// multiply_springs for the springs [0, 4 floor(count / 4)), four at a time: the same operations in the same order on
// each spring (the library is built without contraction into fused multiply-adds), and the sums updated spring by
// spring in order, so the result is bit for bit the scalar one. Returns the number of springs done.
CLOTHCD_SIMD_ENTRY std::size_t multiply_springs_wide(const double* n0, const double* n1, const double* n2,
                                                    const double* alpha, const double* beta, const int* a3s,
                                                    const int* b3s, std::size_t count, const double* in,
                                                    double* sum) {
  const std::size_t whole = count / 4 * 4;
  alignas(32) double s[3][4];
  for (std::size_t k = 0; k < whole; k += 4) {
    Doubles d[4], q[3];  // (q0, q1, q2, 0) of the four springs, then the four q0's, q1's and q2's
    for (int l = 0; l < 4; ++l) d[l] = load3(in + a3s[k + l]) - load3(in + b3s[k + l]);
    lanes::transpose3(d, q);
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
CLOTHCD_SIMD_ENTRY Eigen::Index cg_step_wide(double step, const double* p, const double* ap, const double* diagonal,
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
inline Doubles dot3(const Doubles a[3], const Doubles b[3]) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

// The per-spring linearisation of predict_velocities for springs [0, 4 floor(count / 4)), four at a time: the same
// operations in the same order as its scalar loop (the Eigen expressions there), blocks written per field, and rhs and
// diagonal updated spring by spring in order, so the result is bit for bit the scalar one. `rest` and `stiffness`
// hold each spring's rest length and k. Returns the number of springs done.
CLOTHCD_SIMD_ENTRY std::size_t linearise_springs_wide(const double* x, const double* v, const double* rest,
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
    const Doubles length = lanes::sqrt(dot3(d, d));
    const auto ok = length > tiny;  // length > 1e-12 (false for NaN)
    for (int c = 0; c < 3; ++c) n[c] = d[c] / length;
    const Doubles r = load(rest + s), k = load(stiffness + s);
    const Doubles t = one - r / length;
    const Doubles transverse = lanes::select(zero < t, t, zero);  // std::max(0.0, t)
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
    store(n0 + s, lanes::select(ok, n[0], one));
    store(n1 + s, lanes::select(ok, n[1], zero));
    store(n2 + s, lanes::select(ok, n[2], zero));
    store(alpha + s, lanes::select(ok, a, zero));
    store(beta + s, lanes::select(ok, b, zero));
    const unsigned valid = lanes::bits(ok);
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
CLOTHCD_SIMD_ENTRY Eigen::Index cg_direction_wide(double c, const double* z, double* p, Eigen::Index n) {
  const Doubles cs = splat(c);
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) store(p + i, load(z + i) + cs * load(p + i));
  return i;
}
