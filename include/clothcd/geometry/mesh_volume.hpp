#pragma once
/// @file
/// Enclosed volume of a closed triangle mesh and the compactness ratio tau of a bounding volume (paper eqs. 19-21).

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// Signed volume enclosed by `mesh` by the divergence theorem: sum over faces of a . (b x c) / 6. Positive for a closed
/// mesh with outward (counter-clockwise) faces; meaningless for an open mesh. Units: model units cubed. Throws
/// std::invalid_argument for a face index out of range.
[[nodiscard]] double mesh_volume(const TriangleMesh& mesh);

/// Compactness tau = bounding_volume / |mesh_volume(mesh)| (>= 1 for a true bound of a closed mesh; smaller is tighter).
/// Throws std::invalid_argument when the mesh volume is zero.
[[nodiscard]] double compactness(double bounding_volume, const TriangleMesh& mesh);

}  // namespace clothcd::geometry
