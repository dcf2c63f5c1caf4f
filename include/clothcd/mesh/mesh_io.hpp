#pragma once
/// @file
/// Reading meshes through assimp (OBJ, PLY, OFF, STL, 3DS, BLEND, DAE, glTF, ...) and writing OBJ and PLY.

#include <filesystem>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// How load_mesh treats the file's contents.
struct LoadOptions {
  /// Merge vertices with bit-identical positions, across all of the file's meshes (normals and UVs are ignored).
  bool join_identical_vertices = true;
  /// Remove zero-area faces (they are counted in LoadReport either way).
  bool drop_degenerate_faces = true;
};

/// What load_mesh found and changed.
struct LoadReport {
  int source_meshes = 0;             ///< Meshes in the file (all are merged, with their node transforms applied).
  int degenerate_faces_dropped = 0;  ///< Zero-area faces removed.
  int vertices_joined = 0;           ///< Vertices merged into an identical one.
};

/// Loads every triangle of a mesh file in any format assimp reads, triangulating polygons and applying node transforms.
/// The result is validated (finite coordinates, indices in range, at least one non-degenerate face).
/// Throws MeshError naming the file and the problem. Note: assimp stores coordinates as float.
[[nodiscard]] TriangleMesh load_mesh(const std::filesystem::path& path, const LoadOptions& options = {},
                                     LoadReport* report = nullptr);

/// Writes `mesh` as Wavefront OBJ (".obj") or ASCII PLY (".ply"), chosen by extension, with coordinates at full double
/// precision (17 significant digits). Throws MeshError on an unknown extension, a non-finite coordinate, a face index
/// out of range (nothing is written then) or a write failure.
void save_mesh(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace clothcd
