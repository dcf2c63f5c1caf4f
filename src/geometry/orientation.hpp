#pragma once
/// @file
/// Exact orientation predicates on double coordinates: the sign of a 3x3 determinant (orient3d) or of a 2x2 one on a
/// coordinate-plane projection (orient2d), decided by a floating-point filter with a proven error bound
/// (geometry/orientation_filter.hpp) and, when the filter cannot tell, exactly on floating-point expansions
/// (geometry/expansion_orientation.hpp), or in GMP integers where those could lose bits to underflow or overflow. The
/// triangle intersection test (geometry/triangle_intersection.hpp) runs on them.
#include <Eigen/Core>

namespace clothcd::geometry {

/// A determinant's rounded value and its exact sign.
struct Orientation {
  double value = 0.0;  ///< The determinant evaluated in doubles (its sign may be wrong when `sign` came exactly).
  int sign = 0;        ///< The exact sign: -1, 0 or 1.
};

/// The sign of det[q - p, r - p, s - p]: positive when s lies on the side of the plane p q r that (q - p) x (r - p)
/// points to, zero when the four points are coplanar. Exact for all finite inputs.
[[nodiscard]] Orientation orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                   const Eigen::Vector3d& s);

/// The sign of the 2x2 determinant of (q - p, r - p) projected along `drop_axis` onto the coordinates
/// ((drop_axis + 1) % 3, (drop_axis + 2) % 3): for p, q, r of one triangle, the sign of its normal's `drop_axis`
/// component. Exact for all finite inputs.
[[nodiscard]] Orientation orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                   int drop_axis);

/// orient3d's sign without the filter (its fallback): on expansions, in GMP where they cannot decide.
[[nodiscard]] int exact_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                 const Eigen::Vector3d& s);

/// orient2d's sign without the filter (its fallback): on expansions, in GMP where they cannot decide.
[[nodiscard]] int exact_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                 int drop_axis);

/// orient3d's sign in exact GMP arithmetic only (the last resort, and the reference of the tests).
[[nodiscard]] int gmp_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                               const Eigen::Vector3d& s);

/// orient2d's sign in exact GMP arithmetic only (the last resort, and the reference of the tests).
[[nodiscard]] int gmp_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                               int drop_axis);

}  // namespace clothcd::geometry
