#pragma once
// Private: closed intervals of doubles with outward rounding, for the safe floating-point CCD. Every operation widens
// its rounded-to-nearest result by more than one rounding error, so the true real result of the operation on any real
// numbers inside the operands lies inside the result:
//   - a sum or difference is exact when its result is subnormal (gradual underflow), so 2^-51 of its magnitude is
//     enough: exact zeros stay exact, and no subnormal number is ever made out of nothing;
//   - a product underflows only when its exact value is below 2^-1022 in magnitude, which needs an operand endpoint
//     that is non-zero and below 2^-511 (a product of two larger numbers is at least 2^-1022); only then is 2^-1022
//     added as well.
// Why not always add a tiny absolute term: zero endpoints are common (axis-aligned or integer queries) and would turn
// into subnormal numbers, whose products cost about 30x a normal product on Intel CPUs (microcode assists); with the
// public handcrafted CCD queries that tripled the mean time per query on an Intel Xeon.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace clothcd::ccd::detail {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

/// Below a sum's rounded result by more than its rounding error.
inline double sum_down(double x) {
  return x - std::fabs(x) * 0x1p-51;
}
/// Above a sum's rounded result by more than its rounding error.
inline double sum_up(double x) {
  return x + std::fabs(x) * 0x1p-51;
}

inline Interval exact(double x) {
  return {x, x};
}
inline Interval hull(const Interval& a, const Interval& b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval operator+(const Interval& a, const Interval& b) {
  return {sum_down(a.lo + b.lo), sum_up(a.hi + b.hi)};
}
inline Interval operator-(const Interval& a, const Interval& b) {
  return {sum_down(a.lo - b.hi), sum_up(a.hi - b.lo)};
}

/// True when the double is non-zero and below 2^-511 in magnitude (a product with it may underflow): its magnitude's
/// bit pattern minus one, compared unsigned with that of 2^-511 minus one (zero wraps to the largest value).
inline bool tiny_nonzero(double x) {
  constexpr std::uint64_t kMagnitude = 0x7fffffffffffffffull, kTiny = 0x2000000000000000ull;  // bits of 2^-511
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return ((bits & kMagnitude) - 1) < kTiny - 1;
}

/// The rounded product bounds lo <= hi moved outwards by their rounding errors; `may_underflow`: an operand was tiny.
inline Interval widened_product(double lo, double hi, bool may_underflow) {
  const double underflow = may_underflow ? 0x1p-1022 : 0.0;
  return {lo - (std::fabs(lo) * 0x1p-51 + underflow), hi + (std::fabs(hi) * 0x1p-51 + underflow)};
}

inline Interval operator*(const Interval& a, const Interval& b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  const bool tiny = tiny_nonzero(a.lo) | tiny_nonzero(a.hi) | tiny_nonzero(b.lo) | tiny_nonzero(b.hi);
  return widened_product(std::min(std::min(p[0], p[1]), std::min(p[2], p[3])),
                         std::max(std::max(p[0], p[1]), std::max(p[2], p[3])), tiny);
}

/// x times c, for a double c in [2^-511, 2^511] (a time in the step, 1/2, 2, 3): the same enclosure as exact(c) * x
/// with two products, and only x's endpoints can make them underflow.
inline Interval scaled(const Interval& x, double c) {
  return widened_product(x.lo * c, x.hi * c, tiny_nonzero(x.lo) | tiny_nonzero(x.hi));
}

/// Sign certain under the enclosure: 1 or -1, else 0 (zero inside, or NaN bounds).
inline int certain_sign(const Interval& a) {
  return a.lo > 0.0 ? 1 : (a.hi < 0.0 ? -1 : 0);
}

}  // namespace clothcd::ccd::detail
