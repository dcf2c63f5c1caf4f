#pragma once
// Private: univariate polynomials with exact rational (GMP) coefficients, Sturm root counting, exact root isolation in
// [0, 1] and exact sign evaluation at real algebraic points. Used only by the slow exact CCD reference.
#include <gmpxx.h>

#include <vector>

namespace clothcd::ccd::exact {

/// Polynomial sum c[i] t^i with rational coefficients; trimmed (no trailing zero coefficients; zero = empty).
struct Polynomial {
  std::vector<mpq_class> c;
};

[[nodiscard]] Polynomial constant(const mpq_class& value);
/// a + b t.
[[nodiscard]] Polynomial linear(const mpq_class& a, const mpq_class& b);
[[nodiscard]] Polynomial operator+(const Polynomial& p, const Polynomial& q);
[[nodiscard]] Polynomial operator-(const Polynomial& p, const Polynomial& q);
[[nodiscard]] Polynomial operator*(const Polynomial& p, const Polynomial& q);
[[nodiscard]] int degree(const Polynomial& p);  ///< -1 for the zero polynomial.
[[nodiscard]] bool is_zero(const Polynomial& p);
[[nodiscard]] mpq_class evaluate(const Polynomial& p, const mpq_class& t);
[[nodiscard]] int sign_at(const Polynomial& p, const mpq_class& t);
/// p with its repeated factors removed (p / gcd(p, p')); same roots, all simple. p must be non-zero.
[[nodiscard]] Polynomial square_free(const Polynomial& p);
/// Number of distinct roots of the square-free p in the open interval (lo, hi); p(lo) and p(hi) must be non-zero.
[[nodiscard]] int count_roots(const Polynomial& p, const mpq_class& lo, const mpq_class& hi);
/// Monic greatest common divisor (zero when both are zero).
[[nodiscard]] Polynomial gcd(const Polynomial& p, const Polynomial& q);

/// A real algebraic number in [0, 1]: either the rational `value` (is_rational), or the only root of the square-free
/// `poly` in the open interval (lo, hi), with poly(lo) != 0, poly(hi) != 0.
struct AlgebraicPoint {
  bool is_rational = true;
  mpq_class value;
  Polynomial poly;
  mpq_class lo, hi;
};

/// All distinct roots in [0, 1] of the non-zero polynomial p, in increasing order.
[[nodiscard]] std::vector<AlgebraicPoint> roots_in_unit_interval(const Polynomial& p);

/// A polynomial with its square-free part and that part's Sturm sequence, computed once for many sign queries.
struct PreparedPolynomial {
  Polynomial p;
  Polynomial square_free;
  std::vector<Polynomial> sturm;
};

[[nodiscard]] PreparedPolynomial prepare(const Polynomial& p);

/// Exact sign (-1, 0, 1) of f at the point. May shrink the point's isolating interval (or find it rational); the point
/// stays the same number.
[[nodiscard]] int sign_at(AlgebraicPoint& point, const PreparedPolynomial& f);

/// Shrinks the point's isolating interval until no polynomial of `others` has a root in [lo, hi] other than the point
/// itself (or until the point turns out rational): then lo and hi lie in the open pieces next to the point.
void isolate_from(AlgebraicPoint& point, const std::vector<PreparedPolynomial>& others);

/// Shrinks the point's isolating interval by exact bisection until hi - lo <= width (or the point turns out rational).
void narrow(AlgebraicPoint& point, const mpq_class& width);

}  // namespace clothcd::ccd::exact
