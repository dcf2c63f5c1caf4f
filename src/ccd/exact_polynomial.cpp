// Exact rational polynomial arithmetic for the CCD reference: Euclid's gcd, square-free parts, Sturm's theorem
// (number of distinct roots in an interval = sign variations at lo minus at hi), bisection root isolation and the sign
// of a polynomial at a real algebraic number (decided by a common-factor test, else by an isolating interval free of
// the polynomial's roots).
#include "ccd/exact_polynomial.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace clothcd::ccd::exact {

namespace {

Polynomial trimmed(Polynomial p) {
  while (!p.c.empty() && p.c.back() == 0) p.c.pop_back();
  return p;
}

// p times a positive rational so that its coefficients are coprime integers: same roots, same signs everywhere.
Polynomial primitive(Polynomial p) {
  if (is_zero(p)) return p;
  mpz_class denominator_lcm = 1;
  for (const mpq_class& c : p.c) mpz_lcm(denominator_lcm.get_mpz_t(), denominator_lcm.get_mpz_t(), c.get_den_mpz_t());
  mpz_class numerator_gcd = 0;
  for (const mpq_class& c : p.c) {
    const mpz_class scaled = c.get_num() * (denominator_lcm / c.get_den());
    mpz_gcd(numerator_gcd.get_mpz_t(), numerator_gcd.get_mpz_t(), scaled.get_mpz_t());
  }
  for (mpq_class& c : p.c) c = mpq_class(mpz_class(c.get_num() * (denominator_lcm / c.get_den())) / numerator_gcd);
  return p;
}

Polynomial derivative(const Polynomial& p) {
  Polynomial d;
  for (std::size_t i = 1; i < p.c.size(); ++i) d.c.push_back(p.c[i] * static_cast<long>(i));
  return trimmed(std::move(d));
}

// Quotient and remainder of p / q (q non-zero).
std::pair<Polynomial, Polynomial> divide(const Polynomial& p, const Polynomial& q) {
  assert(!is_zero(q));
  Polynomial r = p;
  Polynomial quotient;
  const int dq = degree(q);
  if (degree(r) >= dq) quotient.c.assign(static_cast<std::size_t>(degree(r) - dq + 1), mpq_class(0));
  while (!is_zero(r) && degree(r) >= dq) {
    const int shift = degree(r) - dq;
    const mpq_class factor = r.c.back() / q.c.back();
    quotient.c[static_cast<std::size_t>(shift)] = factor;
    for (int i = 0; i <= dq; ++i) r.c[static_cast<std::size_t>(i + shift)] -= factor * q.c[static_cast<std::size_t>(i)];
    r.c.pop_back();  // the leading coefficient cancels exactly
    r = trimmed(std::move(r));
  }
  return {trimmed(std::move(quotient)), r};
}

int sign_variations(const std::vector<Polynomial>& sequence, const mpq_class& t) {
  int variations = 0;
  int previous = 0;
  for (const Polynomial& p : sequence) {
    const int s = sign_at(p, t);
    if (s == 0) continue;
    if (previous != 0 && s != previous) ++variations;
    previous = s;
  }
  return variations;
}

std::vector<Polynomial> sturm_sequence(const Polynomial& p) {
  // Positive scalings keep every sign variation, so each member is kept in small integer form.
  std::vector<Polynomial> sequence{primitive(p), primitive(derivative(p))};
  while (!is_zero(sequence.back())) {
    const Polynomial remainder = divide(sequence[sequence.size() - 2], sequence.back()).second;
    if (is_zero(remainder)) break;
    sequence.push_back(primitive(constant(0) - remainder));
  }
  return sequence;
}

void isolate(const Polynomial& p, const mpq_class& lo, const mpq_class& hi, std::vector<AlgebraicPoint>& out) {
  const int n = count_roots(p, lo, hi);
  if (n == 0) return;
  if (n == 1) {
    out.push_back(AlgebraicPoint{false, mpq_class(0), p, lo, hi});
    return;
  }
  const mpq_class mid = (lo + hi) / 2;
  if (sign_at(p, mid) == 0) {
    // Deflate the rational root so that mid is no longer a root of the polynomial isolated on either side.
    const Polynomial deflated = primitive(divide(p, linear(-mid, 1)).first);
    isolate(deflated, lo, mid, out);
    out.push_back(AlgebraicPoint{true, mid, {}, mid, mid});
    isolate(deflated, mid, hi, out);
    return;
  }
  isolate(p, lo, mid, out);
  isolate(p, mid, hi, out);
}

void bisect(AlgebraicPoint& point) {
  const mpq_class mid = (point.lo + point.hi) / 2;
  const int s_mid = sign_at(point.poly, mid);
  if (s_mid == 0) {
    point.is_rational = true;
    point.value = mid;
    point.lo = point.hi = mid;
    return;
  }
  if (s_mid == sign_at(point.poly, point.lo)) {
    point.lo = mid;
  } else {
    point.hi = mid;
  }
}

int count_roots(const PreparedPolynomial& f, const mpq_class& lo, const mpq_class& hi) {
  return sign_variations(f.sturm, lo) - sign_variations(f.sturm, hi);
}

// True when f vanishes at the (irrational) point: gcd(point.poly, f) divides the square-free point.poly, so its roots
// in (lo, hi) are at most the point itself, simple, and its values at lo and hi are non-zero.
bool shares_point(const AlgebraicPoint& point, const PreparedPolynomial& f) {
  const Polynomial common = gcd(point.poly, f.square_free);
  return degree(common) >= 1 && sign_at(common, point.lo) * sign_at(common, point.hi) < 0;
}

// True when f has no root in [lo, hi] (call only when f does not vanish at the point).
bool free_of_roots(const AlgebraicPoint& point, const PreparedPolynomial& f) {
  return sign_at(f.square_free, point.lo) != 0 && sign_at(f.square_free, point.hi) != 0 &&
         count_roots(f, point.lo, point.hi) == 0;
}

}  // namespace

Polynomial constant(const mpq_class& value) {
  return trimmed(Polynomial{{value}});
}

Polynomial linear(const mpq_class& a, const mpq_class& b) {
  return trimmed(Polynomial{{a, b}});
}

Polynomial operator+(const Polynomial& p, const Polynomial& q) {
  Polynomial r;
  r.c.assign(std::max(p.c.size(), q.c.size()), mpq_class(0));
  for (std::size_t i = 0; i < p.c.size(); ++i) r.c[i] += p.c[i];
  for (std::size_t i = 0; i < q.c.size(); ++i) r.c[i] += q.c[i];
  return trimmed(std::move(r));
}

Polynomial operator-(const Polynomial& p, const Polynomial& q) {
  Polynomial r;
  r.c.assign(std::max(p.c.size(), q.c.size()), mpq_class(0));
  for (std::size_t i = 0; i < p.c.size(); ++i) r.c[i] += p.c[i];
  for (std::size_t i = 0; i < q.c.size(); ++i) r.c[i] -= q.c[i];
  return trimmed(std::move(r));
}

Polynomial operator*(const Polynomial& p, const Polynomial& q) {
  if (is_zero(p) || is_zero(q)) return {};
  Polynomial r;
  r.c.assign(p.c.size() + q.c.size() - 1, mpq_class(0));
  for (std::size_t i = 0; i < p.c.size(); ++i)
    for (std::size_t j = 0; j < q.c.size(); ++j) r.c[i + j] += p.c[i] * q.c[j];
  return trimmed(std::move(r));
}

int degree(const Polynomial& p) {
  return static_cast<int>(p.c.size()) - 1;
}

bool is_zero(const Polynomial& p) {
  return p.c.empty();
}

mpq_class evaluate(const Polynomial& p, const mpq_class& t) {
  mpq_class value = 0;
  for (std::size_t i = p.c.size(); i-- > 0;) value = value * t + p.c[i];
  return value;
}

int sign_at(const Polynomial& p, const mpq_class& t) {
  const bool integer_coefficients =
      std::all_of(p.c.begin(), p.c.end(), [](const mpq_class& c) { return c.get_den() == 1; });
  if (!integer_coefficients) return sgn(evaluate(p, t));
  // With t = a / b (b > 0): sign p(t) = sign(sum c_i a^i b^(n - i)), all in integers (no gcd per operation).
  const mpz_class& a = t.get_num();
  const mpz_class& b = t.get_den();
  mpz_class value = 0;
  mpz_class b_power = 1;
  for (std::size_t i = p.c.size(); i-- > 0;) {
    value = value * a + p.c[i].get_num() * b_power;
    b_power *= b;
  }
  return sgn(value);
}

Polynomial square_free(const Polynomial& p) {
  assert(!is_zero(p));
  const Polynomial g = gcd(p, derivative(p));
  if (degree(g) <= 0) return primitive(p);
  return primitive(divide(p, g).first);
}

int count_roots(const Polynomial& p, const mpq_class& lo, const mpq_class& hi) {
  if (degree(p) <= 0) return 0;
  const std::vector<Polynomial> sequence = sturm_sequence(p);
  return sign_variations(sequence, lo) - sign_variations(sequence, hi);
}

Polynomial gcd(const Polynomial& p, const Polynomial& q) {
  Polynomial a = p;
  Polynomial b = q;
  while (!is_zero(b)) {
    Polynomial r = divide(a, b).second;
    a = std::move(b);
    b = std::move(r);
  }
  if (is_zero(a)) return a;
  a = primitive(std::move(a));
  if (a.c.back() < 0)
    for (mpq_class& coefficient : a.c) coefficient = -coefficient;
  return a;
}

std::vector<AlgebraicPoint> roots_in_unit_interval(const Polynomial& p) {
  assert(!is_zero(p));
  std::vector<AlgebraicPoint> roots;
  Polynomial f = square_free(p);
  const bool root_at_0 = sign_at(f, 0) == 0;
  const bool root_at_1 = sign_at(f, 1) == 0;
  if (root_at_0) f = primitive(divide(f, linear(0, 1)).first);
  if (root_at_1) f = primitive(divide(f, linear(-1, 1)).first);
  if (root_at_0) roots.push_back(AlgebraicPoint{true, mpq_class(0), {}, mpq_class(0), mpq_class(0)});
  isolate(f, 0, 1, roots);
  if (root_at_1) roots.push_back(AlgebraicPoint{true, mpq_class(1), {}, mpq_class(1), mpq_class(1)});
  return roots;
}

PreparedPolynomial prepare(const Polynomial& p) {
  PreparedPolynomial prepared{p, {}, {}};
  if (degree(p) >= 1) {
    prepared.square_free = square_free(p);
    prepared.sturm = sturm_sequence(prepared.square_free);
  }
  return prepared;
}

int sign_at(AlgebraicPoint& point, const PreparedPolynomial& f) {
  if (degree(f.p) <= 0) return is_zero(f.p) ? 0 : sgn(f.p.c[0]);
  if (point.is_rational) return sign_at(f.p, point.value);
  if (shares_point(point, f)) return 0;
  while (!point.is_rational && !free_of_roots(point, f)) bisect(point);
  return sign_at(f.p, point.is_rational ? point.value : point.lo);
}

void isolate_from(AlgebraicPoint& point, const std::vector<PreparedPolynomial>& others) {
  for (const PreparedPolynomial& f : others) {
    if (degree(f.p) <= 0 || point.is_rational) continue;
    const int expected = shares_point(point, f) ? 1 : 0;
    // Shrinking keeps the property for the polynomials already handled.
    while (!point.is_rational && (sign_at(f.square_free, point.lo) == 0 || sign_at(f.square_free, point.hi) == 0 ||
                                  count_roots(f, point.lo, point.hi) != expected))
      bisect(point);
  }
}

void narrow(AlgebraicPoint& point, const mpq_class& width) {
  while (!point.is_rational && point.hi - point.lo > width) bisect(point);
}

}  // namespace clothcd::ccd::exact
