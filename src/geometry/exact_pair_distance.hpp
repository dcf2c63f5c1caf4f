#pragma once
/// @file
/// The slow, plainly exact reference of the pair distances (geometry/pair_distance.hpp), for tests: every candidate
/// pair of features (vertex-vertex, vertex-edge, and the inside candidate when the exact projection or common
/// perpendicular falls strictly inside) with its exact squared distance in GMP rationals; the distance is their
/// minimum, and the type the first candidate in the documented order that attains it.
#include <gmpxx.h>

#include <Eigen/Dense>

#include "clothcd/geometry/distance_type.hpp"

namespace clothcd::geometry {

/// The exact squared distance of a pair and the feature of its closest points.
struct ExactPairDistance {
  mpq_class squared_distance;                   ///< Exact squared distance of the closed primitives.
  DistanceType type = DistanceType::PointFace;  ///< Exact type, ties broken as pair_distance.hpp documents.
};

/// Reference distance of point p and the closed triangle t0 t1 t2.
[[nodiscard]] ExactPairDistance exact_point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                              const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

/// Reference distance of the closed segments a0 a1 and b0 b1.
[[nodiscard]] ExactPairDistance exact_segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                               const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

}  // namespace clothcd::geometry
