// Floating-point expansion arithmetic after Shewchuk (1997): error-free sum (Knuth's two-sum) and product (Dekker's
// splitting), the linear-time sum of two expansions (merge by magnitude, then a chain of two-sums) and the product
// of an expansion with a double, all with zero elimination. Each routine keeps the expansions strongly
// non-overlapping, which the next routine needs (round-to-nearest-even double arithmetic, no FMA contraction: ISO
// C++ mode).
#include "geometry/expansion.hpp"

#include <algorithm>
#include <cmath>

namespace clothcd::geometry::detail {

namespace {

// x + y = a + b exactly, x = fl(a + b).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// Same for |a| >= |b| (or a == 0).
inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  y = b - (x - a);
}

// a = hi + lo with both halves of at most 26 significant bits.
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}

// x + y = a * b exactly, x = fl(a * b).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double a_hi, a_lo, b_hi, b_lo;
  split(a, a_hi, a_lo);
  split(b, b_hi, b_lo);
  const double error1 = x - a_hi * b_hi;
  const double error2 = error1 - a_lo * b_hi;
  const double error3 = error2 - a_hi * b_lo;
  y = a_lo * b_lo - error3;
}

// Shewchuk's compression of the non-overlapping terms in[0..n) into out (n doubles of room, may alias in): the same
// value, non-adjacent, usually far fewer terms. Returns the number of terms written.
std::size_t compress_terms(const double* in, std::size_t n, double* out) {
  if (n < 2) {
    if (n == 1) out[0] = in[0];
    return n;
  }
  // Top-down pass: sums from the largest term, keeping the parts that do not fit; then bottom-up: the same from the
  // smallest kept part, emitting the errors.
  double g[2 * Expansion::kCapacity];
  std::size_t bottom = n - 1;
  double q = in[bottom];
  for (std::size_t i = n - 1; i-- > 0;) {
    double sum, rest;
    fast_two_sum(q, in[i], sum, rest);
    if (rest != 0.0) {
      g[bottom--] = sum;
      q = rest;
    } else {
      q = sum;
    }
  }
  g[bottom] = q;
  std::size_t count = 0;
  for (std::size_t i = bottom + 1; i < n; ++i) {
    double sum, rest;
    fast_two_sum(g[i], q, sum, rest);
    if (rest != 0.0) out[count++] = rest;
    q = sum;
  }
  if (q != 0.0) out[count++] = q;
  return count;
}

}  // namespace

void sum_into(const Expansion& e, const Expansion& f, double f_sign, Expansion& h) {
  if (e.size_ == 0 || f.size_ == 0) {
    if (e.size_ == 0) {
      for (std::size_t i = 0; i < f.size_; ++i) h.terms_[i] = f_sign * f.terms_[i];
      h.size_ = f.size_;
    } else {
      h = e;
    }
    return;
  }
  if (e.size_ == 1 && f.size_ == 1) {  // the common short case: one two-sum
    double x, y;
    two_sum(e.terms_[0], f_sign * f.terms_[0], x, y);
    h.size_ = 0;
    if (y != 0.0) h.terms_[h.size_++] = y;
    if (x != 0.0) h.terms_[h.size_++] = x;
    return;
  }
  double merged[2 * Expansion::kCapacity];
  const std::size_t count = e.size_ + f.size_;
  {  // merge by magnitude
    std::size_t i = 0, j = 0, k = 0;
    while (i < e.size_ && j < f.size_) {
      const double fj = f_sign * f.terms_[j];
      if (std::fabs(fj) < std::fabs(e.terms_[i])) {
        merged[k++] = fj;
        ++j;
      } else {
        merged[k++] = e.terms_[i++];
      }
    }
    while (i < e.size_) merged[k++] = e.terms_[i++];
    while (j < f.size_) merged[k++] = f_sign * f.terms_[j++];
  }
  // The chain of two-sums writes straight into h when it fits, else over the merged terms already consumed (index
  // kept <= i), compressed afterwards.
  double* out = count <= Expansion::kCapacity ? h.terms_ : merged;
  std::size_t written = 0;
  double q = 0.0;  // the first two-sum just takes merged[0] (exactly, no rest)
  for (std::size_t i = 0; i < count; ++i) {
    double q_new, rest;
    two_sum(q, merged[i], q_new, rest);
    if (rest != 0.0) out[written++] = rest;
    q = q_new;
  }
  if (q != 0.0) out[written++] = q;
  if (out == merged) {
    if (written > Expansion::kCapacity) written = compress_terms(merged, written, merged);
    if (written > Expansion::kCapacity) throw ExpansionCapacityExceeded();
    for (std::size_t i = 0; i < written; ++i) h.terms_[i] = merged[i];
  }
  h.size_ = written;
}

Expansion::Expansion(double x) {
  if (x != 0.0) push(x);
}

Expansion Expansion::difference(double a, double b) {
  Expansion r;
  double x, y;
  two_sum(a, -b, x, y);
  if (y != 0.0) r.push(y);
  if (x != 0.0) r.push(x);
  return r;
}

// sum_into reads e and f completely (into the merge buffer, or two locals) before it writes h, so h may be either.
Expansion& Expansion::operator+=(const Expansion& b) {
  sum_into(*this, b, 1.0, *this);
  return *this;
}

Expansion& Expansion::operator-=(const Expansion& b) {
  sum_into(*this, b, -1.0, *this);
  return *this;
}

Expansion operator+(const Expansion& a, const Expansion& b) {
  Expansion r;
  sum_into(a, b, 1.0, r);
  return r;
}

Expansion Expansion::operator-() const {
  Expansion r = *this;
  for (std::size_t i = 0; i < r.size_; ++i) r.terms_[i] = -r.terms_[i];
  return r;
}

Expansion operator-(const Expansion& a, const Expansion& b) {
  Expansion r;
  sum_into(a, b, -1.0, r);
  return r;
}

Expansion Expansion::scaled(double b) const {
  Expansion r;
  if (size_ == 0 || b == 0.0) return r;
  double q, rest;
  two_product(terms_[0], b, q, rest);
  if (rest != 0.0) r.push(rest);
  for (std::size_t i = 1; i < size_; ++i) {
    double product_hi, product_lo, sum;
    two_product(terms_[i], b, product_hi, product_lo);
    two_sum(q, product_lo, sum, rest);
    if (rest != 0.0) r.push(rest);
    fast_two_sum(product_hi, sum, q, rest);
    if (rest != 0.0) r.push(rest);
  }
  if (q != 0.0) r.push(q);
  return r;
}

Expansion operator*(const Expansion& a, const Expansion& b) {
  const Expansion& longer = a.size_ >= b.size_ ? a : b;
  const Expansion& shorter = a.size_ >= b.size_ ? b : a;
  if (shorter.size_ == 0) return Expansion();
  Expansion r = longer.scaled(shorter.terms_[0]);
  for (std::size_t i = 1; i < shorter.size_; ++i) {
    r += longer.scaled(shorter.terms_[i]);
    if (r.size_ > Expansion::kCapacity / 2) r = r.compressed();  // keeps the partial sums within the capacity
  }
  return shorter.size_ > 1 ? r.compressed() : r;
}

Expansion Expansion::compressed() const {
  Expansion r;
  r.size_ = compress_terms(terms_, size_, r.terms_);
  return r;
}

int Expansion::top_exponent() const {
  return std::ilogb(terms_[size_ - 1]);
}

int Expansion::bottom_exponent() const {
  int exponent = 0;
  const double mantissa = std::frexp(terms_[0], &exponent);  // 1/2 <= |mantissa| < 1
  auto bits = static_cast<long long>(std::fabs(std::ldexp(mantissa, 53)));
  int lowest = exponent - 53;
  for (; (bits & 1) == 0; bits >>= 1) ++lowest;
  return lowest;
}

Expansion Expansion::times_power_of_two(int k) const {
  Expansion r = *this;
  if (k >= -1022 && k <= 1023) {
    // 2^k is a normal double: the product is x 2^k correctly rounded, as ldexp gives it (no library call per term).
    const double factor = std::ldexp(1.0, k);
    for (std::size_t i = 0; i < size_; ++i) r.terms_[i] = terms_[i] * factor;
  } else {
    for (std::size_t i = 0; i < size_; ++i) r.terms_[i] = std::ldexp(terms_[i], k);
  }
  return r;
}

double Expansion::estimate() const {
  double s = 0.0;
  for (std::size_t i = 0; i < size_; ++i) s += terms_[i];
  return s;
}

}  // namespace clothcd::geometry::detail
