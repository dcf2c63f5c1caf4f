#pragma once
/// @file
/// Floating-point polynomials of coordinate differences that carry their own rounding-error bound, so that a sign or a
/// comparison decided in double precision is certain (the filter of the pair distances, geometry/pair_distance.hpp).
///
/// A Bounded<K> holds the computed value of a polynomial P and the computed value M of the same expression tree with
/// every input replaced by its absolute value and every subtraction by an addition. K counts roundings: an input that
/// is a double has K = 0, the rounded difference of two doubles K = 1, a sum or difference max(K1, K2) + 1 and a
/// product K1 + K2 + 1. Expanding the tree, every monomial m_i of P is computed as m_i (1 + theta_i) with
/// |theta_i| <= gamma_K = K u / (1 - K u), u = 2^-53 (Higham, "Accuracy and Stability of Numerical Algorithms", 3.1:
/// the factors (1 + delta) of the roundings on the monomial's path multiply, and a product node's path runs through
/// both factors). Hence |value - P| <= gamma_K A with A = sum |m_i|, and the same argument on the absolute tree gives
/// M >= (1 - gamma_K) A, so |value - P| <= gamma_K / (1 - gamma_K) M. For K <= 40 that is below (K + 1) u M, and
/// rounding the bound itself (one product, one sum) costs less than the further u M of error_bound's (K + 2) u M.
///
/// Underflow adds an absolute error of at most 2^-1075 per product beyond that model, which later products multiply
/// by their other factors. The callers keep every coordinate at most 2^100 in magnitude (so differences are at most
/// 2^101) and use polynomials of degree at most 6 with fewer than 64 products: an underflow then costs less than
/// 64 * 2^-1075 * (3 * 2^101)^5 < 2^-550 in all, which kUnderflowSlack covers. Overflow cannot go unnoticed: M is at
/// least |value| node by node, so an overflowed value comes with an infinite bound and is never certain. Without
/// fused multiply-add (the library is built with -ffp-contract=off) every operation is one IEEE rounding.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace clothcd::geometry::bounded {

/// Absolute error that covers underflow in the polynomials of coordinates at most kLargestCoordinate in magnitude.
inline constexpr double kUnderflowSlack = 0x1p-500;

/// The largest coordinate magnitude (and distance) for which the bounds hold.
inline constexpr double kLargestCoordinate = 0x1p100;

/// A computed polynomial value with the computed absolute tree `magnitude`, K roundings deep (see the file comment).
template <int K>
struct Bounded {
  double value;      ///< The polynomial as computed.
  double magnitude;  ///< The same tree on absolute values, as computed (>= 0).
};

/// A vector of three Bounded<K> components, stored as two Eigen vectors.
template <int K>
struct BoundedVector {
  Eigen::Vector3d value;      ///< Components as computed.
  Eigen::Vector3d magnitude;  ///< Their absolute trees as computed.
};

/// A double taken as it is (no rounding).
[[nodiscard]] inline Bounded<0> exact(double x) {
  return {x, std::abs(x)};
}

/// The rounded difference a - b of two points, one rounding per component.
[[nodiscard]] inline BoundedVector<1> difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d v = a - b;
  return {v, v.cwiseAbs()};
}

/// Sum of two bounded values.
template <int A, int B>
[[nodiscard]] inline Bounded<std::max(A, B) + 1> operator+(const Bounded<A>& x, const Bounded<B>& y) {
  return {x.value + y.value, x.magnitude + y.magnitude};
}

/// Difference of two bounded values.
template <int A, int B>
[[nodiscard]] inline Bounded<std::max(A, B) + 1> operator-(const Bounded<A>& x, const Bounded<B>& y) {
  return {x.value - y.value, x.magnitude + y.magnitude};
}

/// Product of two bounded values.
template <int A, int B>
[[nodiscard]] inline Bounded<A + B + 1> operator*(const Bounded<A>& x, const Bounded<B>& y) {
  return {x.value * y.value, x.magnitude * y.magnitude};
}

/// Dot product, summed as (x + y) + z.
template <int A, int B>
[[nodiscard]] inline Bounded<A + B + 3> dot(const BoundedVector<A>& x, const BoundedVector<B>& y) {
  const Eigen::Vector3d& v = x.value;
  const Eigen::Vector3d& w = y.value;
  const Eigen::Vector3d& m = x.magnitude;
  const Eigen::Vector3d& n = y.magnitude;
  return {(v.x() * w.x() + v.y() * w.y()) + v.z() * w.z(), (m.x() * n.x() + m.y() * n.y()) + m.z() * n.z()};
}

/// Cross product.
template <int A, int B>
[[nodiscard]] inline BoundedVector<A + B + 2> cross(const BoundedVector<A>& x, const BoundedVector<B>& y) {
  const Eigen::Vector3d& v = x.value;
  const Eigen::Vector3d& w = y.value;
  const Eigen::Vector3d& m = x.magnitude;
  const Eigen::Vector3d& n = y.magnitude;
  return {Eigen::Vector3d(v.y() * w.z() - v.z() * w.y(), v.z() * w.x() - v.x() * w.z(), v.x() * w.y() - v.y() * w.x()),
          Eigen::Vector3d(m.y() * n.z() + m.z() * n.y(), m.z() * n.x() + m.x() * n.z(), m.x() * n.y() + m.y() * n.x())};
}

/// An upper bound of |x.value - P| (file comment).
template <int K>
[[nodiscard]] inline double error_bound(const Bounded<K>& x) {
  static_assert(K <= 40, "the bound's constant assumes at most 40 roundings");
  constexpr double kFactor = (K + 2) * 0x1p-53;
  return kFactor * x.magnitude + kUnderflowSlack;
}

/// The certain sign of P: +1 or -1, or 0 when the rounding error might hide it (P itself may be 0 then).
template <int K>
[[nodiscard]] inline int sign(const Bounded<K>& x) {
  const double bound = error_bound(x);
  if (x.value > bound) return 1;
  if (x.value < -bound) return -1;
  return 0;
}

/// An upper bound of the Euclidean norm of x.value - V (the sum of the components' bounds).
template <int K>
[[nodiscard]] inline double error_bound(const BoundedVector<K>& x) {
  const Bounded<K> cx{x.value.x(), x.magnitude.x()}, cy{x.value.y(), x.magnitude.y()}, cz{x.value.z(), x.magnitude.z()};
  return (error_bound(cx) + error_bound(cy)) + error_bound(cz);
}

/// True when |x.value| is within relative error 2^-Bits of |P| (and P != 0).
template <int Bits, int K>
[[nodiscard]] inline bool accurate_length(const Bounded<K>& x) {
  constexpr double kTolerance = 1.0 / static_cast<double>(1ull << Bits);
  return error_bound(x) <= kTolerance * std::abs(x.value);
}

/// True when the length of x.value is within relative error 2^-Bits of that of V (and V != 0), given its squared
/// length as computed (within 3 u of the exact square of x.value's length; the factor 1/2 in the test covers the
/// roundings of both of its sides).
template <int Bits, int K>
[[nodiscard]] inline bool accurate_length(const BoundedVector<K>& x, double squared_length) {
  constexpr double kTolerance = 1.0 / static_cast<double>(1ull << Bits);
  const double error = error_bound(x);
  return error * error <= 0.5 * kTolerance * kTolerance * squared_length;
}

}  // namespace clothcd::geometry::bounded
