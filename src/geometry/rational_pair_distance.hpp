#pragma once
/// @file
/// The exact tier of the pair distances (geometry/pair_distance.hpp): the closest feature and the squared distance in
/// GMP rationals, for the pairs the floating-point filter cannot certify. The same region tests as the filter, every
/// sign exact, with the degenerate primitives (zero-area triangles, zero-length and parallel segments) and the ties
/// resolved as pair_distance.hpp documents.
#include <gmpxx.h>

#include <Eigen/Dense>

#include "geometry/pair_distance.hpp"

namespace clothcd::geometry {

/// A pair's distance record with its exact squared distance.
struct RationalDistance {
  PairDistance record;         ///< Distance (rounded from the exact square), parameters, direction, exact type.
  mpq_class squared_distance;  ///< The exact squared distance.
};

/// The exact distance of point p and the closed triangle t0 t1 t2.
[[nodiscard]] RationalDistance rational_point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                                const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

/// The exact distance of the closed segments a0 a1 and b0 b1.
[[nodiscard]] RationalDistance rational_segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                                 const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

}  // namespace clothcd::geometry
