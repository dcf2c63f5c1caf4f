#pragma once
/// @file
/// Exact distances of the primitive pairs of one state: a point against a closed triangle (vertex-face) and two closed
/// segments (edge-edge), on the double coordinates taken as real numbers. Whether a pair is within a distance is
/// decided exactly; the reported distance is within kDistanceRelativeError of the exact one, and the closest feature
/// (DistanceType) is the exact one.
///
/// A floating-point filter with certified error bounds (geometry/bounded_arithmetic.hpp) decides almost every pair;
/// the rest go to an exact tier in GMP rationals (geometry/pair_distance_exact.hpp).
///
/// Where the closest points are not unique, or lie on more than one feature (zero-area triangles, coincident vertices,
/// parallel or zero-length segments, touching primitives), the type is the first feature in this order that holds a
/// closest point (pair): vertex-face PointVertex0, 1, 2, PointEdge0, 1, 2, PointFace; edge-edge VertexA0VertexB0,
/// VertexA0VertexB1, VertexA1VertexB0, VertexA1VertexB1, VertexA0Edge, VertexA1Edge, EdgeVertexB0, EdgeVertexB1,
/// EdgeEdge. A zero-area triangle is never PointFace, and a zero-length edge is always at its first vertex.
#include <Eigen/Dense>

#include <array>

#include "clothcd/geometry/distance_type.hpp"

namespace clothcd::geometry {

/// The distance of a pair and where it is attained.
struct PairDistance {
  /// Distance of the closed primitives, within kDistanceRelativeError of the exact one (0 exactly when they touch).
  double distance = 0.0;
  /// Vertex-face: barycentric weights (w1, w2) of the triangle's closest point, of t1 and t2 (w0 = 1 - w1 - w2).
  /// Edge-edge: (s, u) in [0, 1], the closest points being a0 + s (a1 - a0) and b0 + u (b1 - b0). Rounded.
  std::array<double, 2> parameters{};
  /// Unit vector from the closest point of the second primitive (triangle, edge b) to that of the first (the point,
  /// edge a); zero when they touch.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  DistanceType type = DistanceType::PointFace;  ///< The feature of the closest points (file comment for ties).
};

/// True exactly when the distance of point p and the closed triangle t0 t1 t2 is less than d (d > 0; a pair at
/// exactly d is not within); then `out` holds the pair's distance record. `out` is left as it was otherwise.
bool point_triangle_within(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                           const Eigen::Vector3d& t2, double d, PairDistance& out);

/// True exactly when the distance of the closed segments a0 a1 and b0 b1 is less than d (d > 0); then `out` holds the
/// pair's distance record. `out` is left as it was otherwise.
bool segment_segment_within(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                            const Eigen::Vector3d& b1, double d, PairDistance& out);

/// The distance record of point p and the closed triangle t0 t1 t2.
[[nodiscard]] PairDistance point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                   const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

/// The distance record of the closed segments a0 a1 and b0 b1.
[[nodiscard]] PairDistance segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                    const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

}  // namespace clothcd::geometry
