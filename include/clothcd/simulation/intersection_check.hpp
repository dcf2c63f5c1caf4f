#pragma once
/// @file
/// An independent, discrete check of a simulation frame: counts intersecting triangle pairs (cloth-cloth pairs sharing no
/// vertex, and cloth-obstacle pairs) with its own uniform grid, and measures the smallest cloth-obstacle distance.
/// It shares no code with the collision detector, so it can catch that detector's misses.

#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::simulation {

/// One triangle given by its three corners.
struct Triangle {
  Eigen::Vector3d a;  ///< First corner.
  Eigen::Vector3d b;  ///< Second corner.
  Eigen::Vector3d c;  ///< Third corner.
};

/// True when the two closed triangles share at least one point (touching counts). Coplanar pairs are tested in 2D.
/// Degenerate (zero-area) triangles are tested as their edges.
[[nodiscard]] bool triangles_intersect(const Triangle& t, const Triangle& u);

/// Euclidean distance between two closed triangles (0 when they intersect).
[[nodiscard]] double triangle_distance(const Triangle& t, const Triangle& u);

/// Settings of the frame check.
struct IntersectionCheckSettings {
  double cell_size = 0;       ///< Grid cell edge, scene units; 0 picks twice the cloth's mean edge length.
  double distance_margin = 0.05;  ///< Cloth-obstacle pairs farther apart than this are not measured, scene units.
};

/// What the frame check found.
struct IntersectionReport {
  long cloth_cloth_pairs = 0;     ///< Intersecting cloth triangle pairs that share no vertex.
  long cloth_obstacle_pairs = 0;  ///< Intersecting (cloth triangle, obstacle triangle) pairs, over all obstacles.
  /// Smallest cloth-obstacle triangle distance; +infinity when every pair is farther than the margin or there is no
  /// obstacle.
  double min_cloth_obstacle_distance = 0;

  /// Sum of both counts.
  [[nodiscard]] long intersecting_pairs() const { return cloth_cloth_pairs + cloth_obstacle_pairs; }
};

/// Checks one frame: `cloth` (its faces index `cloth_positions`, #V x 3) against itself and every obstacle mesh in its
/// current position. Uses a uniform grid; results equal check_frame_brute_force's.
[[nodiscard]] IntersectionReport check_frame(const Faces& cloth_faces, const Vertices& cloth_positions,
                                             const std::vector<TriangleMesh>& obstacles,
                                             const IntersectionCheckSettings& settings = {});

/// The slow reference of check_frame: every pair of triangles, O(F^2).
[[nodiscard]] IntersectionReport check_frame_brute_force(const Faces& cloth_faces, const Vertices& cloth_positions,
                                                         const std::vector<TriangleMesh>& obstacles,
                                                         const IntersectionCheckSettings& settings = {});

}  // namespace clothcd::simulation
