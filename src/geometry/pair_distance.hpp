#pragma once
/// @file
/// Exact distances of the primitive pairs of one state: a point against a closed triangle (vertex-face) and two closed
/// segments (edge-edge), on the (finite) double coordinates taken as real numbers. Whether a pair is within a distance
/// is decided exactly; the reported distance is within kDistanceRelativeError of the exact one (below the normal range,
/// 2^-1022, within 2^-1074 of it), and the closest feature (DistanceType) is the exact one.
///
/// A floating-point filter with certified error bounds (geometry/bounded_arithmetic.hpp) decides almost every pair;
/// the rest go to an exact tier in GMP rationals (geometry/rational_pair_distance.hpp).
///
/// Where the closest points are not unique, or lie on more than one feature (zero-area triangles, coincident vertices,
/// parallel or zero-length segments, touching primitives), the type is the first feature in this order that holds a
/// closest point (pair): vertex-face PointVertex0, 1, 2, PointEdge0, 1, 2, PointFace; edge-edge VertexA0VertexB0,
/// VertexA0VertexB1, VertexA1VertexB0, VertexA1VertexB1, VertexA0Edge, VertexA1Edge, EdgeVertexB0, EdgeVertexB1,
/// EdgeEdge. A zero-area triangle is never PointFace, and a zero-length edge is always at its first vertex.
///
/// The module also keeps the double-precision closest points its users had before the exact queries, unchanged bit for
/// bit: point_triangle_closest and segment_segment_closest (the CCD's thickness test; with the contact parameters of
/// degenerate primitives), and Ericson's Voronoi-region closest points (C. Ericson, "Real-Time Collision Detection",
/// 5.1.5, 5.1.9) closest_point_on_triangle, point_triangle_distance_squared and segment_segment_distance_squared (the
/// Hausdorff measure and the simulation), and the CCD's contact frames (contact parameters and normal at a time of
/// impact).
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

/// True exactly when the distance of point p and the closed triangle t0 t1 t2 is less than d (a pair at exactly d is
/// not within; false for d <= 0 or NaN, true for d = infinity); then `out` holds the pair's distance record. `out` is
/// left as it was otherwise.
bool point_triangle_within(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                           const Eigen::Vector3d& t2, double d, PairDistance& out);

/// True exactly when the distance of the closed segments a0 a1 and b0 b1 is less than d (as point_triangle_within);
/// then `out` holds the pair's distance record. `out` is left as it was otherwise.
bool segment_segment_within(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                            const Eigen::Vector3d& b1, double d, PairDistance& out);

/// The distance record of point p and the closed triangle t0 t1 t2.
[[nodiscard]] PairDistance point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                   const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

/// The distance record of the closed segments a0 a1 and b0 b1.
[[nodiscard]] PairDistance segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                    const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

// Double-precision closest points (not exact; geometry/pair_distance_closest_points.cpp).

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

// Ericson's closest points in double precision (geometry/pair_distance_voronoi_regions.cpp).

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

/// The closest point of the closed segment p1 q1 minus that of p2 q2 (either may be a point).
[[nodiscard]] Eigen::Vector3d segment_segment_offset(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                                     const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

/// Squared distance between the closed segments p1 q1 and p2 q2 (either may be a point; segment_segment_offset's).
[[nodiscard]] double segment_segment_distance_squared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                                      const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

// The CCD's contact frames (geometry/pair_distance_contact_frame.cpp).

/// The contact parameters and normal of a pair at a contact, in double precision.
struct ContactFrame {
  /// Vertex-face: the barycentric weights (w1, w2) of the vertex's projection onto the triangle's plane (not clamped to
  /// the triangle). Edge-edge: the parameters (s, u) of the closest points of the two lines, each clamped to [0, 1].
  /// Zero when the triangle or the pair of edges is degenerate (the normal equations' determinant is not positive).
  std::array<double, 2> parameters{};
  /// Unit face normal or cross product of the edges, turned towards the first primitive; zero when degenerate.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// The contact frame of point x[0] and triangle x[1] x[2] x[3]; the normal has a non-negative dot product with
/// towards_first.
[[nodiscard]] ContactFrame point_triangle_contact_frame(const std::array<Eigen::Vector3d, 4>& x,
                                                        const Eigen::Vector3d& towards_first);

/// The contact frame of the edges x[0] x[1] and x[2] x[3] (parameters s on the first, u on the second).
[[nodiscard]] ContactFrame segment_segment_contact_frame(const std::array<Eigen::Vector3d, 4>& x,
                                                         const Eigen::Vector3d& towards_first);

}  // namespace clothcd::geometry
