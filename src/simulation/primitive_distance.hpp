#pragma once
// Private: distances between the primitives of a collision pair (defined in triangle_geometry.cpp).
#include <Eigen/Dense>

#include "clothcd/simulation/intersection_check.hpp"

namespace clothcd::simulation {

/// Squared distance between the closed segments p1q1 and p2q2 (either may be a point).
double segment_segment_distance_squared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                                        const Eigen::Vector3d& q2);

/// Squared distance from point p to the closed, non-degenerate triangle t.
double point_triangle_distance_squared(const Eigen::Vector3d& p, const Triangle& t);

}  // namespace clothcd::simulation
