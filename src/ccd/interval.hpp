#pragma once
// Private: closed intervals of doubles with outward rounding, for the exact tiers of the CCD (their sign filters) and
// the shared-plane test. Every operation widens its rounded-to-nearest result by more than one rounding error, so the
// true real result of the operation on any real numbers inside the operands lies inside the result:
//   - a sum or difference is exact when its result is subnormal (gradual underflow), so 2^-51 of its magnitude is
//     enough: exact zeros stay exact, and no subnormal number is ever made out of nothing;
//   - a product underflows only when its exact value is below 2^-1022 in magnitude, which needs an operand endpoint
//     that is non-zero and below 2^-511 (a product of two larger numbers is at least 2^-1022); only then is 2^-1022
//     added as well.
// Why not always add a tiny absolute term: zero endpoints are common (axis-aligned or integer queries) and would turn
// into subnormal numbers, whose products cost about 30x a normal product on Intel CPUs (microcode assists); with the
// public handcrafted CCD queries that tripled the mean time per query on an Intel Xeon.
#include <algorithm>
#include <cstdint>

#include "support/simd.hpp"

namespace clothcd::ccd::detail {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

// The operations below keep an interval's bounds in one two-lane vector, {lo, hi}: each lane computes exactly what the
// formulas in their comments give (a product's four endpoint products are compared in another order than one by
// one, which can only change the sign of a zero bound).
namespace bounds {

namespace lanes = simd::baseline_lanes;
using lanes::Doubles;
using lanes::Masks;

[[gnu::always_inline]] inline Doubles of(const Interval& a) { return Doubles{a.lo, a.hi}; }
[[gnu::always_inline]] inline Interval to_interval(Doubles v) { return {v[0], v[1]}; }

/// {lo - error_lo, hi + error_hi}: the rounded bounds v moved outwards by error >= 0.
[[gnu::always_inline]] inline Doubles outward(Doubles v, Doubles error) {
  return v + lanes::as_doubles(lanes::as_bits(error) ^ Masks{INT64_MIN, 0});
}

/// Lanes that are non-zero and below 2^-511 in magnitude (a product with them may underflow).
[[gnu::always_inline]] inline Masks tiny_nonzero(Doubles v) {
  const Doubles magnitude = lanes::abs(v);
  return lanes::less(magnitude, lanes::splat(0x1p-511)) & lanes::less(lanes::splat(0.0), magnitude);
}

/// A sum's or difference's rounded bounds moved out by 2^-51 of their magnitudes: {lo - |lo| 2^-51, hi + |hi| 2^-51}.
[[gnu::always_inline]] inline Interval widened_sum(Doubles v) {
  return to_interval(outward(v, lanes::abs(v) * lanes::splat(0x1p-51)));
}

/// A product's rounded bounds moved out by 2^-51 of their magnitudes, plus 2^-1022 when `tiny` has a lane set:
/// {lo - (|lo| 2^-51 + u), hi + (|hi| 2^-51 + u)}.
[[gnu::always_inline]] inline Interval widened_product(Doubles v, Masks tiny) {
  const double underflow = lanes::any(tiny) ? 0x1p-1022 : 0.0;
  return to_interval(outward(v, lanes::abs(v) * lanes::splat(0x1p-51) + lanes::splat(underflow)));
}

}  // namespace bounds

inline Interval exact(double x) {
  return {x, x};
}
/// The rounded {a.lo + b.lo, a.hi + b.hi}, widened.
[[gnu::always_inline]] inline Interval operator+(const Interval& a, const Interval& b) {
  return bounds::widened_sum(bounds::of(a) + bounds::of(b));
}
/// The rounded {a.lo - b.hi, a.hi - b.lo}, widened.
[[gnu::always_inline]] inline Interval operator-(const Interval& a, const Interval& b) {
  return bounds::widened_sum(bounds::of(a) - bounds::lanes::swap(bounds::of(b)));
}

/// The smallest and largest of the four rounded endpoint products, widened (with 2^-1022 when an endpoint is tiny).
[[gnu::always_inline]] inline Interval operator*(const Interval& a, const Interval& b) {
  using namespace simd::baseline_lanes;
  const Doubles bb = bounds::of(b);
  const Doubles from_lo = splat(a.lo) * bb, from_hi = splat(a.hi) * bb;
  const Doubles low = min(from_lo, from_hi), high = max(from_lo, from_hi);
  const Doubles v{std::min(low[0], low[1]), std::max(high[0], high[1])};
  return bounds::widened_product(v, bounds::tiny_nonzero(bounds::of(a)) | bounds::tiny_nonzero(bb));
}

/// x times c, for a double c in [2^-511, 2^511] (a time in the step, 1/2, 2, 3): the same enclosure as exact(c) * x
/// with two products, and only x's endpoints can make them underflow.
[[gnu::always_inline]] inline Interval scaled(const Interval& x, double c) {
  const bounds::Doubles v = bounds::of(x);
  return bounds::widened_product(v * bounds::lanes::splat(c), bounds::tiny_nonzero(v));
}

/// Sign certain under the enclosure: 1 or -1, else 0 (zero inside, or NaN bounds).
inline int certain_sign(const Interval& a) {
  return a.lo > 0.0 ? 1 : (a.hi < 0.0 ? -1 : 0);
}

}  // namespace clothcd::ccd::detail
