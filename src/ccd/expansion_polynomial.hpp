#pragma once
// Private: polynomials in the time t of degree at most 3 with exact floating-point expansion coefficients, for the
// expansion tier of the thickness-0 CCD (expansion_collision.cpp): exact sums, differences, products and values, the
// signs of their Bernstein coefficients on a piece, their signs at grid and rational times, and pseudo-division.
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <optional>

#include "geometry/expansion.hpp"

namespace clothcd::ccd::detail {

/// The exact numbers of the expansion tier.
using geometry::detail::Expansion;
/// Thrown when an expansion would outgrow its capacity.
using geometry::detail::ExpansionCapacityExceeded;

/// sum c[i] t^i, degree at most 3.
struct Poly {
  std::array<Expansion, 4> c;  ///< The coefficients c[0..n).
  std::size_t n = 0;           ///< Number of coefficients.

  /// The zero polynomial (no coefficients).
  Poly() = default;
  /// The coefficients c[0], c[1], ... in order (at most 4).
  Poly(std::initializer_list<Expansion> coefficients) {
    for (const Expansion& e : coefficients) c[n++] = e;
  }
  /// count zero coefficients; throws ExpansionCapacityExceeded above 4 (a product above degree 3).
  explicit Poly(std::size_t count) : n(count) {
    if (count > c.size()) throw ExpansionCapacityExceeded();
  }
  /// Number of coefficients (zero ones included).
  [[nodiscard]] std::size_t size() const { return n; }
  /// Whether there is no coefficient.
  [[nodiscard]] bool empty() const { return n == 0; }
  /// Coefficient i (of t^i).
  Expansion& operator[](std::size_t i) { return c[i]; }
  /// Coefficient i (of t^i).
  const Expansion& operator[](std::size_t i) const { return c[i]; }
};

/// Exact p + q.
[[nodiscard]] Poly operator+(const Poly& p, const Poly& q);
/// Exact p - q.
[[nodiscard]] Poly operator-(const Poly& p, const Poly& q);
/// Exact p q (ExpansionCapacityExceeded above degree 3).
[[nodiscard]] Poly operator*(const Poly& p, const Poly& q);

/// The index of the highest non-zero coefficient, -1 for the zero polynomial (inline: asked before nearly every
/// sign).
[[nodiscard]] inline int degree(const Poly& p) {
  for (int i = static_cast<int>(p.size()) - 1; i >= 0; --i)
    if (!p[static_cast<std::size_t>(i)].is_zero()) return i;
  return -1;
}

/// Exact p(t) (at t = 0 and t = 1 without products).
[[nodiscard]] Expansion evaluate(const Poly& p, const Expansion& t);

/// Signs of the n + 1 Bernstein coefficients of a polynomial of degree n (at most 3) on a piece.
struct BernsteinSigns {
  std::array<int, 4> sign{};  ///< sign[0..count): -1, 0 or 1.
  int count = 0;              ///< n + 1.
};

/// Signs of the Bernstein coefficients (times positive constants) of p, of degree n in 0..3, on [lo, lo + width]
/// (from interval enclosures when those decide every sign, else exact).
[[nodiscard]] BernsteinSigns bernstein_signs(const Poly& p, int n, const Expansion& lo, const Expansion& width);

/// The sign of p (degree n >= 1) at every t in [0, 1] with |t - m| <= distance when plain double arithmetic on the
/// rounded coefficients proves it, else 0: |p(t) - p~(m)| is below the coefficients' and the evaluation's rounding
/// (relative 1e-13 of sum |p_i|) plus the largest slope on [0, 1] times the distance. Sets value to p~(m). Inline:
/// the first test of nearly every sign at a grid time or a bracketed root.
[[nodiscard]] inline int filtered_sign(const Poly& p, int n, double m, double distance, double& value) {
  double magnitude = 0.0, slope = 0.0;
  value = 0.0;
  for (int i = n; i >= 0; --i) {
    const double coefficient = p[static_cast<std::size_t>(i)].estimate();
    value = value * m + coefficient;
    magnitude += std::fabs(coefficient);
    slope += i * std::fabs(coefficient);
  }
  const double bound = 1e-13 * magnitude + slope * (1.0 + 1e-13) * distance + 0x1p-1000;
  return value > bound ? 1 : (value < -bound ? -1 : 0);
}

/// Exact sign of p at the grid time t (filtered first), with an estimate of p(t).
int sign_at_time(const Poly& p, const Expansion& t, double& estimate);

/// Exact sign of p at the rational num / den (den != 0): the sign of sum p_i num^i den^(n - i), times sign(den)^n.
/// num and den are scaled by one power of two, and so are p's coefficients, to centre their exponents on 0; nullopt
/// when the products could still leave the double exponent range.
[[nodiscard]] std::optional<int> sign_at_rational(const Poly& p, Expansion num, Expansion den);

/// The result of a pseudo-division of a by b: lc(b)^k a = quotient b + remainder.
struct PseudoDivision {
  Poly quotient, remainder;  ///< The remainder's degree is below b's.
};

/// Pseudo-division of a by b (degree of b >= 1): lc(b)^k a = q b + r with r of degree below b's; nullopt when the
/// products could leave the double exponent range.
[[nodiscard]] std::optional<PseudoDivision> pseudo_divide(Poly a, const Poly& b);

}  // namespace clothcd::ccd::detail
