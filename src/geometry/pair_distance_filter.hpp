#pragma once
/// @file
/// What the two filters of the pair distances (vertex-face and edge-edge, geometry/pair_distance.hpp) share: the
/// outcome of a filter, the certain tests against the asked distance d, and the driver that hands undecided pairs to
/// the exact tier (geometry/rational_pair_distance.hpp).
#include <gmpxx.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <limits>

#include "geometry/bounded_arithmetic.hpp"
#include "geometry/pair_distance.hpp"
#include "geometry/rational_pair_distance.hpp"

namespace clothcd::geometry::filter {

/// How a filter ended.
enum class Outcome {
  Apart,      ///< Certainly not within d.
  Found,      ///< Within d (or no d was asked), and the record is filled.
  Undecided,  ///< The exact tier decides.
};

/// The four points of a pair.
using Points = std::array<const Eigen::Vector3d*, 4>;

/// True when every coordinate is at most bounded::kLargestCoordinate in magnitude (false for NaN).
[[nodiscard]] inline bool in_range(const Points& x) {
  double largest = 0.0;
  for (const Eigen::Vector3d* point : x) largest = std::max(largest, point->cwiseAbs().maxCoeff());
  return largest <= bounded::kLargestCoordinate;
}

/// True when the rounded difference a - b exceeds d: then the exact one does (rounding is monotonic and d is a double).
[[nodiscard]] inline bool gap_exceeds(double a, double b, double d) {
  return a - b > d;
}

/// The certain sign of d^2 den - num: +1 when num / den < d^2 (den > 0), -1 when it is above, 0 when uncertain.
template <int KN, int KD>
[[nodiscard]] int within_sign(const bounded::Bounded<KN>& num, const bounded::Bounded<KD>& den, double d) {
  const bounded::Bounded<0> dd = bounded::exact(d);
  return bounded::sign(dd * dd * den - num);
}

/// The certain sign of d^2 - num.
template <int KN>
[[nodiscard]] int within_sign(const bounded::Bounded<KN>& num, double d) {
  const bounded::Bounded<0> dd = bounded::exact(d);
  return bounded::sign(dd * dd - num);
}

/// Bits of relative accuracy accurate_length must certify for the length whose square is the numerator of a squared
/// distance, and for the denominator's.
inline constexpr int kNumeratorBits = 41;
inline constexpr int kDenominatorBits = 42;

/// The distance sqrt(num / den) from squared lengths num and den computed from vectors (or scalars) whose lengths are
/// within 2^-41 and 2^-42 of the exact ones (accurate_length): the computed squares are within 2 (2^-41) + 4 u and
/// 2 (2^-42) + 4 u of the exact squares, the rounded quotient within 2^-40 + 2^-41 + 9 u, and its correctly rounded
/// square root within 2^-41 + 2^-42 + 5 u < kDistanceRelativeError (2^-40) of the exact distance.
[[nodiscard]] inline double distance_from_squares(double num, double den) {
  return std::sqrt(num / den);
}

/// within(): the filter (`Filter(double d, bool limited, PairDistance&) -> Outcome`), and the exact tier
/// (`Exact() -> RationalDistance`) for what it leaves undecided and for d beyond the filter's range.
template <typename Filter, typename Exact>
bool decide_within(double d, PairDistance& out, Filter filter, Exact exact) {
  if (!(d > 0.0)) return false;
  if (d <= bounded::kLargestCoordinate) {
    const Outcome outcome = filter(d, true, out);
    if (outcome != Outcome::Undecided) return outcome == Outcome::Found;
  }
  RationalDistance rational = exact();
  if (d != std::numeric_limits<double>::infinity()) {
    const mpq_class dq(d);
    if (!(rational.squared_distance < dq * dq)) return false;
  }
  out = rational.record;
  return true;
}

/// distance(): the filter without a limit, else the exact tier.
template <typename Filter, typename Exact>
PairDistance decide_distance(Filter filter, Exact exact) {
  PairDistance out;
  if (filter(0.0, false, out) == Outcome::Found) return out;
  return exact().record;
}

}  // namespace clothcd::geometry::filter
