#pragma once
/// @file
/// The slow reference of the triangle intersection test (geometry/triangle_intersection.hpp), in GMP rationals only
/// and by another construction: every edge of each triangle is clipped exactly against the other triangle (an
/// interval of the edge's parameter), and the triangles intersect iff an endpoint of some clipped interval lies
/// outside the hull of the shared corners. Those endpoints include every extreme point of the common set (an extreme
/// point lies on an edge of one triangle, and is an end of that edge's common part), and the common set is their
/// convex hull. Degenerate triangles are clipped against as the segment or point they cover. Also the fast test's
/// fallback for pairs with a degenerate triangle.
#include "geometry/triangle_intersection.hpp"

namespace clothcd::geometry {

/// intersect_triangles' answer in exact rational arithmetic; the crossing is the first clipped endpoint outside the
/// shared corners' hull (edges of a first), rounded from its exact value.
[[nodiscard]] TriangleContact exact_intersect_triangles(const Triangle& a, const Triangle& b,
                                                        const SharedCorners& shared = {});

}  // namespace clothcd::geometry
