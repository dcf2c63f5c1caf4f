#pragma once
// Private, for library sources only (they are compiled with -ffp-contract=off, which the error bounds below need: one
// rounding per operation): the floating-point filters of the orientation predicates, inline for the triangle test.
//
// Error bounds (u = 2^-53, the unit roundoff; gamma_k = k u / (1 - k u)). Without underflow or overflow every
// operation returns x (1 + delta) with |delta| <= u.
//
// orient3d: e1 = q - p, e2 = r - p, d = s - p are rounded differences, n = e1 x e2 is computed as
// n0 = e1y e2z - e1z e2y (and cyclically), and det = (d0 n0 + d1 n1) + d2 n2. Each of the six monomials of the
// determinant is then the exact monomial of the exact differences times at most 8 factors (1 + delta): three
// differences, the product, the difference of products, the product with d, and at most two additions. So
// |computed - exact| <= gamma_8 * sum |monomials| <= 6 gamma_8 Mx My Mz, where Mx = max(|e1x|, |e2x|, |dx|) over the
// exact differences. The rounded differences give mx >= Mx (1 - u), so the bound is <= 48 u (1 + 20 u) mx my mz.
// The filter compares against fl(fl(fl(49 u mx) my) mz) >= 49 u (1 - u)^3 mx my mz, which exceeds it by more than
// u mx my mz. That margin pays for underflow: when mx, my, mz >= 2^-300, a product can still underflow (one tiny
// component), but every underflow adds an absolute error <= 2^-1075, later multiplied by at most one factor below
// 2 mx (or my, mz), in all < 2^-1068 max(mx, my, mz), far below u mx my mz >= 2^-653 max(mx, my, mz); and the bound's
// own products stay normal (>= 2^-947). Overflow turns some intermediate into an infinity or NaN, which stays one to
// the end, so a non-finite determinant is never decided. When an axis maximum is exactly zero, all four points have
// one coordinate in common and the determinant is exactly zero (and so is every computed monomial). Below 2^-300 the
// filter does not decide.
//
// orient2d: e = q - p, f = r - p (two coordinates), det = e_i f_j - e_j f_i: each monomial carries at most 4 factors
// (two differences, the product, the subtraction), so |computed - exact| <= gamma_4 * 2 Mi Mj <= 8 u (1 + 8 u) mi mj;
// the filter uses fl(fl(9 u mi) mj), with the margin u mi mj > 2^-953 covering the two products' underflow
// (< 2^-1074) when mi, mj >= 2^-450.
//
// Where those bounds cannot decide (nearly coplanar or collinear points), a second, dynamic bound on the permanent:
// the sum of the monomials' magnitudes, computed from the same rounded values.
// orient3d: P = (|d0| a0 + |d1| a1) + |d2| a2 with a0 = |e1y e2z| + |e1z e2y| (and cyclically). Each term of P is a
// monomial of the rounded differences times at most 5 factors (1 + delta) (the product and the sum in a_k, the
// product with |d_k|, two additions), and that monomial is the exact one times 3, so M = sum |exact monomials| <=
// P / (1 - u)^8 and |computed - exact| <= gamma_8 M <= 8 u (1 + 17 u) P. The filter compares against 9 u P (exact:
// 9 u is a power of two times 9, and 9 u P stays normal), a margin above the error of more than u P / 2. With
// mx, my, mz >= 2^-300 (checked first), underflow adds fewer than 20 errors of at most 2^-1075 times a factor below
// max(1, 2 max(mx, my, mz)), to the determinant and to P; P >= 2^-950 and P >= 2^-950 max(mx, my, mz) keep them below
// that margin. Overflow makes P or the determinant infinite or NaN, and nothing is decided.
// orient2d: P = |e_i f_j| + |e_j f_i|, each term the exact monomial times at most 4 factors (two differences, the
// product, the sum), so |computed - exact| <= gamma_4 P / (1 - u)^4 <= 4 u (1 + 9 u) P; the filter uses 5 u P, whose
// margin u P / 2 exceeds the at most four products' underflow errors (< 2^-1073) when P >= 2^-950.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/orientation.hpp"

namespace clothcd::geometry::filter {

/// The sign a filter returns when it cannot decide.
inline constexpr int kUndecided = 2;
/// orient3d's bound factor, 49 u.
inline constexpr double kOrient3dFactor = 49.0 * 0x1p-53;
/// orient2d's bound factor, 9 u.
inline constexpr double kOrient2dFactor = 9.0 * 0x1p-53;
/// Below this axis maximum orient3d's products may underflow: the filter does not decide.
inline constexpr double kOrient3dSmallest = 0x1p-300;
/// Below this axis maximum orient2d's products may underflow: the filter does not decide.
inline constexpr double kOrient2dSmallest = 0x1p-450;
/// orient3d's permanent bound factor, 9 u.
inline constexpr double kOrient3dPermanentFactor = 9.0 * 0x1p-53;
/// orient2d's permanent bound factor, 5 u.
inline constexpr double kOrient2dPermanentFactor = 5.0 * 0x1p-53;
/// Below this permanent (absolute, and relative to the largest axis maximum) underflow may exceed the margin of the
/// permanent bounds: they do not decide.
inline constexpr double kPermanentSmallest = 0x1p-950;

/// The sign of `value` when its magnitude exceeds `bound` (and is finite), else kUndecided.
inline int decide(double value, double bound) {
  const double magnitude = std::abs(value);
  if (magnitude > bound && magnitude <= std::numeric_limits<double>::max()) return value > 0.0 ? 1 : -1;
  return kUndecided;
}

/// The sign of `value` when its magnitude exceeds `factor` times the permanent, which is large enough for that bound
/// (see above; `largest_extent` is orient3d's largest axis maximum, 0 for orient2d), else kUndecided.
inline int decide_on_permanent(double value, double permanent, double factor, double largest_extent) {
  if (!(permanent >= kPermanentSmallest && permanent >= kPermanentSmallest * largest_extent)) return kUndecided;
  return decide(value, factor * permanent);
}

/// A triangle's plane prepared for orient3d(a0, a1, a2, x) at many points x (the filter only: the sign may be
/// kUndecided).
class PlaneFilter {
 public:
  /// The plane of a0 a1 a2 (its normal (a1 - a0) x (a2 - a0)).
  PlaneFilter(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2)
      : origin_(a0), e1_(a1 - a0), e2_(a2 - a0) {
    normal_[0] = e1_[1] * e2_[2] - e1_[2] * e2_[1];
    normal_[1] = e1_[2] * e2_[0] - e1_[0] * e2_[2];
    normal_[2] = e1_[0] * e2_[1] - e1_[1] * e2_[0];
    for (int k = 0; k < 3; ++k) extent_[k] = std::max(std::abs(e1_[k]), std::abs(e2_[k]));
  }

  /// det[a1 - a0, a2 - a0, x - a0] and its sign (or kUndecided).
  [[nodiscard]] Orientation side(const Eigen::Vector3d& x) const {
    const double d0 = x[0] - origin_[0], d1 = x[1] - origin_[1], d2 = x[2] - origin_[2];
    const double value = (d0 * normal_[0] + d1 * normal_[1]) + d2 * normal_[2];
    const double mx = std::max(extent_[0], std::abs(d0));
    const double my = std::max(extent_[1], std::abs(d1));
    const double mz = std::max(extent_[2], std::abs(d2));
    const double smallest = std::min(mx, std::min(my, mz));
    if (!(smallest >= kOrient3dSmallest)) return smallest == 0.0 ? Orientation{0.0, 0} : Orientation{value, kUndecided};
    const int sign = decide(value, kOrient3dFactor * mx * my * mz);
    if (sign != kUndecided) return {value, sign};
    const double permanent =
        (std::abs(d0) * normal_permanent(0) + std::abs(d1) * normal_permanent(1)) + std::abs(d2) * normal_permanent(2);
    return {value, decide_on_permanent(value, permanent, kOrient3dPermanentFactor, std::max(mx, std::max(my, mz)))};
  }

  /// The normal's component along `axis` (the orient2d of the triangle projected along it) and its sign (or
  /// kUndecided).
  [[nodiscard]] Orientation normal_component(int axis) const {
    const double mi = extent_[(axis + 1) % 3], mj = extent_[(axis + 2) % 3];
    const double value = normal_[axis];
    const double smallest = std::min(mi, mj);
    if (!(smallest >= kOrient2dSmallest)) return smallest == 0.0 ? Orientation{0.0, 0} : Orientation{value, kUndecided};
    const int sign = decide(value, kOrient2dFactor * mi * mj);
    if (sign != kUndecided) return {value, sign};
    return {value, decide_on_permanent(value, normal_permanent(axis), kOrient2dPermanentFactor, 0.0)};
  }

  /// The normal's component of largest magnitude (in doubles).
  [[nodiscard]] int dominant_axis() const {
    const double x = std::abs(normal_[0]), y = std::abs(normal_[1]), z = std::abs(normal_[2]);
    return x >= y ? (x >= z ? 0 : 2) : (y >= z ? 1 : 2);
  }

 private:
  // |e1_i e2_j| + |e1_j e2_i|: the permanent of the normal's component k.
  [[nodiscard]] double normal_permanent(int k) const {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    return std::abs(e1_[i] * e2_[j]) + std::abs(e1_[j] * e2_[i]);
  }

  Eigen::Vector3d origin_;
  Eigen::Vector3d e1_, e2_;  // the edge vectors a1 - a0, a2 - a0
  double normal_[3];
  double extent_[3];  // max |component| of the two edge vectors, per axis
};

/// orient2d's filter: the determinant and its sign (or kUndecided).
inline Orientation orient2d_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                   int drop_axis) {
  const int i = (drop_axis + 1) % 3, j = (drop_axis + 2) % 3;
  const double ei = q[i] - p[i], ej = q[j] - p[j], fi = r[i] - p[i], fj = r[j] - p[j];
  const double value = ei * fj - ej * fi;
  const double mi = std::max(std::abs(ei), std::abs(fi)), mj = std::max(std::abs(ej), std::abs(fj));
  const double smallest = std::min(mi, mj);
  if (!(smallest >= kOrient2dSmallest)) return smallest == 0.0 ? Orientation{0.0, 0} : Orientation{value, kUndecided};
  const int sign = decide(value, kOrient2dFactor * mi * mj);
  if (sign != kUndecided) return {value, sign};
  const double permanent = std::abs(ei * fj) + std::abs(ej * fi);
  return {value, decide_on_permanent(value, permanent, kOrient2dPermanentFactor, 0.0)};
}

/// orient3d with the exact fallback: the filter, then expansions (GMP where they cannot decide).
inline Orientation orient3d_exact_sign(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                       const Eigen::Vector3d& s) {
  Orientation o = PlaneFilter(p, q, r).side(s);
  if (o.sign == kUndecided) o.sign = exact_orient3d(p, q, r, s);
  return o;
}

/// orient2d with the exact fallback: the filter, then expansions (GMP where they cannot decide).
inline Orientation orient2d_exact_sign(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                       int drop_axis) {
  Orientation o = orient2d_filter(p, q, r, drop_axis);
  if (o.sign == kUndecided) o.sign = exact_orient2d(p, q, r, drop_axis);
  return o;
}

}  // namespace clothcd::geometry::filter
