#pragma once
/// @file
/// Summary facts about a mesh: counts, bounding box, connected components, watertightness, degenerate faces.

#include <Eigen/Dense>

#include <limits>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// What `clothcd info` prints about a mesh.
struct MeshInfo {
  Eigen::Index vertices = 0;        ///< Vertex count.
  Eigen::Index faces = 0;           ///< Face count.
  /// Smallest coordinates over all vertices (+infinity without vertices).
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  /// Largest coordinates over all vertices (-infinity without vertices).
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  int components = 0;               ///< Connected components of faces (faces sharing a vertex are connected).
  bool watertight = false;          ///< Every edge is used by exactly two faces, in opposite directions.
  int boundary_edges = 0;           ///< Edges used by one face.
  int non_manifold_edges = 0;       ///< Edges used by three faces or more.
  int degenerate_faces = 0;         ///< Zero-area faces.
  double surface_area = 0.0;        ///< Sum of triangle areas.
};

/// Computes MeshInfo for a mesh with valid indices (see validate_mesh); an empty mesh gives counts of 0.
[[nodiscard]] MeshInfo compute_mesh_info(const TriangleMesh& mesh);

}  // namespace clothcd
