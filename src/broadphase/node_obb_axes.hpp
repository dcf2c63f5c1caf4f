#pragma once
// Private: where the obstacle-side OBB hierarchy gets the axes of each node. The one place to switch the axis source
// (e.g. to the geometry area's fast adaptive OBB). Extents never come from here: the hierarchy projects the node's
// swept triangle boxes onto the axes, so the box bounds them whatever the axes are.

#include <Eigen/Dense>

#include "broadphase/body_topology.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::broadphase::detail {

/// The triangles of one node: faces[begin, end) of a face index array, with the body's positions at t0 and t1.
struct NodeTriangles {
  const BodyTopology* topology = nullptr;  ///< Body topology.
  const int* faces_begin = nullptr;        ///< First face index of the node.
  const int* faces_end = nullptr;          ///< One past the last face index.
  const Vertices* start = nullptr;         ///< Positions at t0 (#V x 3).
  const Vertices* end = nullptr;           ///< Positions at t1 (#V x 3).
};

/// Orthonormal, right-handed axes (columns) for the OBB of a node's triangles.
[[nodiscard]] Eigen::Matrix3d node_obb_axes(const NodeTriangles& node);

}  // namespace clothcd::broadphase::detail
