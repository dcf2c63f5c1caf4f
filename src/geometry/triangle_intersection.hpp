#pragma once
/// @file
/// The exact intersection test of two closed triangles, with a crossing point to start untangling from. Two triangles
/// intersect when they have a common point outside the convex hull of their shared corners (the corners that are one
/// mesh vertex, given by SharedCorners), the semantics of CGAL's Polygon_mesh_processing::self_intersections:
///   - no shared corner: any common point (touching counts);
///   - one shared vertex v: a common point other than v;
///   - a shared edge pq: a common point off the segment pq. For non-degenerate faces: the two are coplanar and their
///     third corners r, s lie strictly on the same side of the line pq (folded flat onto each other); a dihedral angle,
///     or coplanar on opposite sides, is no intersection. A third corner on the line pq makes its face degenerate
///     (below): such a pair intersects only when both faces are segments of that line reaching beyond p or q on the
///     same side (CGAL's coplanar_orientation is COLLINEAR, not POSITIVE, for a single one);
///   - three shared corners (a duplicated face): never (every common point is in the hull of the shared corners; CGAL
///     does not report them either: its soup test skips identical faces, and two faces of a halfedge mesh with the
///     same three vertices fall in its shared-edge test with a collinear fourth point).
/// Degenerate (zero-area) triangles are the segment or point they cover, by the same rule (CGAL instead reports each
/// degenerate face on its own and pairs it with no other).
///
/// Every decision is exact: orientation signs from geometry/orientation.hpp (a proven floating-point filter, then
/// floating-point expansions, GMP only for coordinates near underflow or overflow). Non-degenerate pairs are decided
/// by those signs (no allocation unless a sign needs GMP); pairs with a degenerate face go to the rational reference
/// (geometry/exact_triangle_intersection.hpp).
#include <Eigen/Core>
#include <array>

namespace clothcd::geometry {

/// A triangle by its three corners.
using Triangle = std::array<Eigen::Vector3d, 3>;

/// Which corners of triangle a are the same mesh vertex as which corners of triangle b (faces of one body). The
/// paired corners must have equal positions, and a corner is in at most one pair.
struct SharedCorners {
  int count = 0;                              ///< Number of pairs, 0 to 3.
  std::array<std::array<int, 2>, 3> pairs{};  ///< (corner of a, corner of b), the first `count` used.
};

/// The shared corners of two faces given by their vertex indices (in one body).
[[nodiscard]] SharedCorners shared_corners(const std::array<int, 3>& face_a, const std::array<int, 3>& face_b);

/// Whether two triangles intersect, and where an edge of one meets the other.
struct TriangleContact {
  bool intersect = false;  ///< Exact.
  bool coplanar = false;   ///< Exact: the six corners lie in one plane (whether or not they intersect).
  /// With intersect: a common point (not in the hull of the shared corners) where an edge of one face meets the
  /// other, rounded: the face of the edge (0 = a, 1 = b), the edge (edge k joins corners k and (k + 1) % 3), the
  /// point's parameter s on it ((1 - s) corner k + s corner k+1) and its barycentric weights (w1, w2) on the other
  /// face ((1 - w1 - w2) corner 0 + w1 corner 1 + w2 corner 2).
  int edge_face = 0;
  int edge = 0;                          ///< The crossing edge's index in its face.
  double edge_parameter = 0.0;           ///< s in [0, 1].
  std::array<double, 2> face_weights{};  ///< (w1, w2) on the other face, w1, w2 >= 0, w1 + w2 <= 1.
};

/// Whether the closed triangles a and b intersect (beyond their shared corners), with a crossing point.
[[nodiscard]] TriangleContact intersect_triangles(const Triangle& a, const Triangle& b,
                                                  const SharedCorners& shared = {});

/// intersect_triangles' yes or no alone (the crossing point is not rounded).
[[nodiscard]] bool triangles_intersect(const Triangle& a, const Triangle& b, const SharedCorners& shared = {});

}  // namespace clothcd::geometry
