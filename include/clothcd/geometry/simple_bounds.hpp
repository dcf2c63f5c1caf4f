#pragma once
/// @file
/// Axis-aligned boxes and minimal bounding spheres of point sets.

#include <vector>

#include "clothcd/geometry/bounding_volumes.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// The smallest axis-aligned box containing every row of `points` (#V x 3). Empty (min > max) when #V is 0.
[[nodiscard]] Aabb compute_aabb(const Vertices& points);

/// The smallest axis-aligned box containing the rows `indices` of `points`. Indices must lie in [0, #V).
[[nodiscard]] Aabb compute_aabb(const Vertices& points, const std::vector<int>& indices);

/// The minimal bounding sphere of the rows of `points` (#V x 3) by Welzl's randomized algorithm (iterative
/// move-to-front form, expected O(#V), fixed seed so the result is deterministic). A final pass grows the radius to the
/// farthest point, so the sphere contains every point even when round-off disturbs the support sets.
/// Empty (radius -1) when #V is 0; radius 0 for a single (or repeated) point.
[[nodiscard]] Sphere compute_bounding_sphere(const Vertices& points);

/// Reference for tests: the sphere centred at the AABB centre with radius the largest distance to a point.
[[nodiscard]] Sphere compute_bounding_sphere_naive(const Vertices& points);

}  // namespace clothcd::geometry
