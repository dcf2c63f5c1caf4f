#pragma once
/// @file
/// Closest points and distances of the primitives of a triangle mesh by Ericson's Voronoi-region tests (C. Ericson,
/// "Real-Time Collision Detection", 5.1.5 closest point on a triangle, 5.1.9 closest points of two segments): the
/// Hausdorff measure and the simulation's distances use them. The CCD's thickness test has its own closest points
/// (geometry/closest_points.hpp), which also give the contact parameters of degenerate primitives.
#include <Eigen/Dense>

namespace clothcd::geometry {

/// How the point of the face region, a + ab vb / d + ac vc / d (d = va + vb + vc), is rounded. The Hausdorff measure
/// and the simulation have always used one each; each keeps its own, so that their results stay the same bit for bit.
enum class FaceRounding {
  Quotient,    ///< a + ab (vb / d) + ac (vc / d): the Hausdorff measure's.
  Reciprocal,  ///< a + ab (vb r) + ac (vc r) with r = 1 / d: the simulation's distances.
};

/// The point of the closed triangle a b c closest to p. A triangle whose Voronoi-region sums vanish (a degenerate one
/// whose edges did not claim p) gives a.
[[nodiscard]] Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                                        FaceRounding rounding = FaceRounding::Quotient);

/// Squared distance from p to the closed triangle a b c (that of closest_point_on_triangle).
[[nodiscard]] double point_triangle_distance_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                                     FaceRounding rounding = FaceRounding::Quotient);

/// Squared distance between the closed segments p1 q1 and p2 q2 (either may be a point).
[[nodiscard]] double segment_segment_distance_squared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                                      const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

}  // namespace clothcd::geometry
