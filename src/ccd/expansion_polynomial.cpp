// Polynomial algebra on floating-point expansions for the expansion tier of the thickness-0 CCD: exact arithmetic and
// values of polynomials of degree at most 3, the signs of their Bernstein coefficients on a piece (Taylor coefficients
// at the piece's start by synthetic division, scaled by powers of its width and combined; outward-rounded interval
// arithmetic first), signs at grid times (a double filter with a rigorous error bound first), exact signs at rational
// times (homogeneous Horner sums after scaling by powers of two, range-checked) and pseudo-division.
#include "ccd/expansion_polynomial.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <optional>

#include "ccd/interval.hpp"

namespace clothcd::ccd::detail {

namespace {

// An enclosure of e: its rounded sum is within 2^-44 of its value for up to 64 non-overlapping components.
Interval enclose(const Expansion& e) {
  const double value = e.estimate();
  const double radius = std::fabs(value) * 0x1p-40;
  return {value - radius, value + radius};
}

// The Bernstein coefficients (times positive constants) on [lo, lo + width] of sum a_i t^i of degree n in 0..3: the
// Taylor coefficients at lo by repeated synthetic division, scaled by width^k, then combined. One algorithm for the
// interval enclosures and the exact expansions; `times(x, c)` multiplies x by the small integer c.
template <class Number, class Times>
std::array<Number, 4> bernstein_coefficients(std::array<Number, 4> a, int n, const Number& lo, const Number& width,
                                             const Times& times) {
  for (int i = 0; i < n; ++i)
    for (int j = n - 1; j >= i; --j) a[j] = a[j] + lo * a[j + 1];
  Number power = width;
  for (int k = 1; k <= n; ++k) {
    a[k] = a[k] * power;
    if (k < n) power = power * width;
  }
  switch (n) {
    case 0:
      return {a[0]};
    case 1:
      return {a[0], a[0] + a[1]};
    case 2:
      return {a[0], times(a[0], 2.0) + a[1], a[0] + a[1] + a[2]};
    default:
      return {a[0], times(a[0], 3.0) + a[1], times(a[0], 3.0) + times(a[1], 2.0) + a[2], a[0] + a[1] + a[2] + a[3]};
  }
}

// The Bernstein signs from outward-rounded interval arithmetic on enclosures of the coefficients; false unless every
// sign is certain (then the exact computation is skipped).
bool filtered_bernstein_signs(const Poly& p, int n, const Expansion& lo, const Expansion& width, BernsteinSigns& out) {
  std::array<Interval, 4> a;
  for (int i = 0; i <= n; ++i) a[static_cast<std::size_t>(i)] = enclose(p[static_cast<std::size_t>(i)]);
  const std::array<Interval, 4> b = bernstein_coefficients(
      a, n, enclose(lo), enclose(width), [](const Interval& x, double c) { return detail::scaled(x, c); });
  out.count = n + 1;
  for (int i = 0; i <= n; ++i) {
    out.sign[static_cast<std::size_t>(i)] = certain_sign(b[static_cast<std::size_t>(i)]);
    if (out.sign[static_cast<std::size_t>(i)] == 0) return false;
  }
  return true;
}

// Binary exponent range of non-zero expansions.
struct BitRange {
  int bottom = INT_MAX, top = INT_MIN;
  void add(const Expansion& e) {
    if (e.is_zero()) return;
    bottom = std::min(bottom, e.bottom_exponent());
    top = std::max(top, e.top_exponent());
  }
  [[nodiscard]] int centring_shift() const { return -(top + bottom) / 2; }
  [[nodiscard]] int half_width() const { return (top - bottom) / 2 + 2; }
};

}  // namespace

Poly operator+(const Poly& p, const Poly& q) {
  Poly r(std::max(p.size(), q.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (i < p.size()) r[i] += p[i];
    if (i < q.size()) r[i] += q[i];
  }
  return r;
}

Poly operator-(const Poly& p, const Poly& q) {
  Poly r(std::max(p.size(), q.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (i < p.size()) r[i] += p[i];
    if (i < q.size()) r[i] -= q[i];
  }
  return r;
}

Poly operator*(const Poly& p, const Poly& q) {
  if (p.empty() || q.empty()) return {};
  Poly r(p.size() + q.size() - 1);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j) r[i + j] += p[i] * q[j];
  return r;
}

Expansion evaluate(const Poly& p, const Expansion& t) {
  Expansion r;
  if (t.is_double(0.0)) return p.empty() ? r : p[0];
  if (t.is_double(1.0)) {  // the sum of the coefficients, no products
    for (std::size_t i = 0; i < p.size(); ++i) r += p[i];
    return r;
  }
  for (std::size_t i = p.size(); i-- > 0;) r = r * t + p[i];
  return r;
}

BernsteinSigns bernstein_signs(const Poly& p, int n, const Expansion& lo, const Expansion& width) {
  BernsteinSigns out;
  if (n >= 1 && filtered_bernstein_signs(p, n, lo, width, out)) return out;
  const std::array<Expansion, 4> b =
      bernstein_coefficients(p.c, n, lo, width, [](const Expansion& x, double c) { return x.scaled(c); });
  out.count = n + 1;
  for (int i = 0; i <= n; ++i) out.sign[static_cast<std::size_t>(i)] = b[static_cast<std::size_t>(i)].sign();
  return out;
}

int sign_at_time(const Poly& p, const Expansion& t, double& estimate) {
  const int n = degree(p);
  const double m = t.estimate();
  if (n >= 1) {
    const int s = filtered_sign(p, n, m, 1e-15 * std::fabs(m) + 0x1p-1000, estimate);
    if (s != 0) return s;
  }
  const Expansion value = evaluate(p, t);
  estimate = value.estimate();
  return value.sign();
}

std::optional<int> sign_at_rational(const Poly& p, Expansion num, Expansion den) {
  const int n = degree(p);
  if (n <= 0) return n < 0 ? 0 : p[0].sign();
  {
    // Filter: p(r) in double at r = num / den rounded (the estimates of up to 64 non-overlapping components are within
    // 2^-47, so r within 2^-45); the coefficients' rounding, r's and Horner's errors stay below 2^-40 of
    // sum |p_i| |r|^i for degree <= 3. Non-finite values fall through to the exact sum.
    const double r = num.estimate() / den.estimate();
    double value = 0.0, magnitude = 0.0;
    for (int i = n; i >= 0; --i) {
      const double coefficient = p[static_cast<std::size_t>(i)].estimate();
      value = value * r + coefficient;
      magnitude = magnitude * std::fabs(r) + std::fabs(coefficient);
    }
    const double bound = magnitude * 0x1p-40 + 0x1p-1000;
    if (std::isfinite(value) && std::isfinite(bound) && std::fabs(value) > bound) return value > 0.0 ? 1 : -1;
  }
  BitRange t_range, p_range;
  t_range.add(num);
  t_range.add(den);
  for (int i = 0; i <= n; ++i) p_range.add(p[static_cast<std::size_t>(i)]);
  if (n * t_range.half_width() + p_range.half_width() + 8 > 1000) return std::nullopt;
  num = num.times_power_of_two(t_range.centring_shift()).compressed();
  den = den.times_power_of_two(t_range.centring_shift()).compressed();
  // sum = den^n p(num / den) by Horner's rule in homogeneous form: s <- s num + p_i den^(n - i), from s = p_n.
  const auto coefficient = [&](int i) {
    return p[static_cast<std::size_t>(i)].times_power_of_two(p_range.centring_shift());
  };
  Expansion sum = coefficient(n);
  Expansion den_power(1.0);
  for (int i = n - 1; i >= 0; --i) {
    den_power = den_power * den;
    sum = sum * num + coefficient(i) * den_power;
  }
  return n % 2 == 1 && den.sign() < 0 ? -sum.sign() : sum.sign();
}

std::optional<PseudoDivision> pseudo_divide(Poly a, const Poly& b) {
  const int nb = degree(b);
  BitRange a_range, b_range;
  for (std::size_t i = 0; i < a.size(); ++i) a_range.add(a[i]);
  for (std::size_t i = 0; i < b.size(); ++i) b_range.add(b[i]);
  const int steps = degree(a) - nb + 1;
  if (a_range.bottom + steps * b_range.bottom < -1000 || a_range.top + steps * (b_range.top + 2) > 1000)
    return std::nullopt;
  const Expansion& lead_b = b[static_cast<std::size_t>(nb)];
  Poly q(static_cast<std::size_t>(std::max(degree(a) - nb + 1, 1)));
  for (int na = degree(a); na >= nb; na = degree(a)) {
    const Expansion lead = a[static_cast<std::size_t>(na)];
    Poly next(static_cast<std::size_t>(na));
    for (int i = 0; i < na; ++i) {
      next[static_cast<std::size_t>(i)] = a[static_cast<std::size_t>(i)] * lead_b;
      if (i >= na - nb)
        next[static_cast<std::size_t>(i)] =
            next[static_cast<std::size_t>(i)] - lead * b[static_cast<std::size_t>(i - (na - nb))];
    }
    a = next;
    // lc(b)^(k+1) a0 = (lc(b) q + lead x^(na - nb)) b + next.
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = q[i] * lead_b;
    q[static_cast<std::size_t>(na - nb)] = q[static_cast<std::size_t>(na - nb)] + lead;
  }
  return PseudoDivision{q, a};
}

}  // namespace clothcd::ccd::detail
