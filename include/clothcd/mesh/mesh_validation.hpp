#pragma once
/// @file
/// Checks a mesh before use: finite coordinates, indices in range, at least one face, degenerate faces.

#include <string>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// Throws MeshError (prefixed with `context`, e.g. the file name) when a coordinate is NaN or infinite, a face index is
/// outside [0, #V), or the mesh has no face.
void validate_mesh(const TriangleMesh& mesh, const std::string& context);

/// True when face `f` has zero area: two equal indices, or three collinear (or coincident) positions. Throws
/// std::out_of_range when `f` or one of its indices is out of range.
[[nodiscard]] bool is_degenerate_face(const TriangleMesh& mesh, Eigen::Index f);

/// Removes the zero-area faces of `mesh` (vertices are kept, so indices stay valid) and returns how many were removed.
/// Throws std::out_of_range for a face index out of range.
int drop_degenerate_faces(TriangleMesh& mesh);

}  // namespace clothcd
