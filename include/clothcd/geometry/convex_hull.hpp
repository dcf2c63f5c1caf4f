#pragma once
/// @file
/// 3-D convex hull of a point set (through Qhull's reentrant library).

#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// A convex hull: which input points are hull vertices, and its triangles as indices into the INPUT points.
struct ConvexHull {
  std::vector<int> vertex_indices;  ///< Rows of the input that are hull vertices, ascending.
  Faces faces;                      ///< #H x 3 triangles (indices into the input rows), outward orientation.
  bool degenerate = false;          ///< True when the points are coplanar, collinear or coincident (no 3-D hull).
};

/// The convex hull of the rows of `points` (#V x 3). For fewer than 4 points or a flat (coplanar, collinear, single
/// point) set the hull is not 3-D: `degenerate` is set, `faces` is empty and `vertex_indices` lists every distinct row
/// (still a superset of the extreme points, so anything that bounds them bounds every point). Throws
/// std::invalid_argument on non-finite coordinates.
[[nodiscard]] ConvexHull compute_convex_hull(const Vertices& points);

}  // namespace clothcd::geometry
