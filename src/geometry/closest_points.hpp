#pragma once
/// @file
/// Closest points between a point and a triangle and between two segments, in double precision, robust to degenerate
/// (zero-area, zero-length, parallel) primitives, with the contact parameters: the CCD's thickness test uses them.
/// The Hausdorff measure and the simulation use Ericson's Voronoi-region tests
/// (geometry/primitive_distance.hpp).
#include <array>

#include <Eigen/Dense>

namespace clothcd::geometry {

/// Closest points of two primitives: their distance, the contact parameters and the two points.
struct ClosestPoints {
  double distance = 0.0;               ///< Euclidean distance between first and second (>= 0).
  std::array<double, 2> parameters{};  ///< Point-triangle: weights (w1, w2) of t1, t2; segments: (s, u) in [0, 1].
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< Closest point on the first primitive (the vertex / edge a).
  Eigen::Vector3d second = Eigen::Vector3d::Zero();  ///< Closest point on the second primitive (triangle / edge b).
};

/// Closest points of point p (first) and triangle t0 t1 t2 (second, = t0 + w1 (t1 - t0) + w2 (t2 - t0)).
/// Near-degenerate triangles (sine of the corner angle below 1e-8) are treated as their three edges, which changes the
/// distance by at most 1e-8 times the longest edge.
[[nodiscard]] ClosestPoints point_triangle_closest(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                   const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

/// Closest points of the segments a0 a1 and b0 b1: first = a0 + s (a1 - a0), second = b0 + u (b1 - b0). Nearly
/// parallel segments (sine below 1e-8) use the endpoint candidates only (error at most 1e-8 times the longer length).
[[nodiscard]] ClosestPoints segment_segment_closest(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                    const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

}  // namespace clothcd::geometry
