#pragma once
/// @file
/// The cheap certain rejection of the pair-distance filters (geometry/pair_distance.hpp): a separating direction.
///
/// For any vector n != 0 and points a* of the first primitive and b* of the second at the exact distance D,
/// min over the vertex pairs (i, j) of n . (a_i - b_j) <= n . (a* - b*) <= D |n| (both primitives are the convex hulls
/// of their vertices, and a linear function takes its minimum over a hull at a vertex). So when every n . (a_i - b_j)
/// exceeds d |n|, then D > d. Any n will do, exact or not: the filters take the difference of closest points computed
/// in plain double, which separates a pair further than d apart by nearly D |n| (most candidates of a flat cloth, where
/// the plane or line distance says nothing).
#include <Eigen/Dense>

#include <cmath>

#include "geometry/bounded_arithmetic.hpp"

namespace clothcd::geometry::filter {

/// A double at least d |n| for the exact Euclidean length |n| (d in (0, kLargestCoordinate]), or infinity when n is
/// zero, too small or not finite, or d |n| is below the normal range, so that nothing passes it.
///
/// The computed square nn = (n0^2 + n1^2) + n2^2 is within gamma_3 of the exact one (terms >= 0); asking nn >= 2^-900
/// makes the products' underflow (at most 3 * 2^-1075) negligible. So |n| <= sqrt(nn) (1 + 1.51 u), the rounded root r
/// has |n| <= r (1 + 2.52 u), and with r d in the normal range, d |n| <= fl(r d) (1 + 3.53 u). The factor 1 + 2^-49 =
/// 1 + 16 u, rounded, still gives more than 1 + 14 u.
[[nodiscard]] inline double scaled_distance_bound(const Eigen::Vector3d& n, double d) {
  constexpr double kInfinity = HUGE_VAL;
  const double nn = n.squaredNorm();
  if (!(nn >= 0x1p-900 && nn <= 0x1p1000)) return kInfinity;
  const double scaled = std::sqrt(nn) * d;
  if (!(scaled >= 0x1p-1000)) return kInfinity;
  return scaled * (1.0 + 0x1p-49);
}

/// True when n . v certainly exceeds `bound` (a double), v the exact difference of which `difference` is the rounded
/// one: the computed dot product less its error bound exceeds it, and the rounded subtraction is monotonic, so the
/// exact one does too. An overflow gives an infinite error bound (bounded_arithmetic.hpp), which never passes.
[[nodiscard]] inline bool projection_exceeds(const Eigen::Vector3d& n, const bounded::BoundedVector<1>& difference,
                                             double bound) {
  const bounded::BoundedVector<0> direction{n, n.cwiseAbs()};
  const bounded::Bounded<4> projection = bounded::dot(direction, difference);
  return projection.value - bounded::error_bound(projection) > bound;
}

/// True when n certainly separates the primitives by more than d: `differences` are the rounded a_i - b_j of every
/// vertex pair (file comment). False whenever that is not certain.
template <typename... Differences>
[[nodiscard]] bool separated_along(const Eigen::Vector3d& n, double d, const Differences&... differences) {
  const double bound = scaled_distance_bound(n, d);
  return (projection_exceeds(n, differences, bound) && ...);
}

}  // namespace clothcd::geometry::filter
