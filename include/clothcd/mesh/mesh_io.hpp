#pragma once
/// @file
/// Reading meshes (OBJ, PLY, OFF and STL by clothcd's own readers at full double precision; 3DS, BLEND, DAE, glTF and
/// the other formats assimp knows through assimp, at float precision) and writing OBJ and PLY exactly.

#include <filesystem>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// How load_mesh treats the file's contents.
struct LoadOptions {
  /// Merge vertices with bit-identical positions, across all of the file's meshes (normals and UVs are ignored), and
  /// drop vertices no face uses.
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

/// Loads every triangle of a mesh file, the format chosen by the extension (any case). OBJ (`v`, `f` lines; others
/// ignored), PLY (ASCII and binary, any scalar types, extra properties and elements skipped), OFF and STL (ASCII and
/// binary; three vertices per triangle, joined by the option below) are read by clothcd's own readers, which keep
/// every coordinate as the file's double bit for bit; polygons are split into a fan of triangles from their first
/// corner. Any other extension assimp knows (3DS, BLEND, DAE, glTF, ...) goes through assimp, which rounds coordinates
/// to float and applies node transforms; the four formats above never do. The result is validated (finite coordinates,
/// indices in range, at least one non-degenerate face). Throws MeshError naming the file, and for the own readers the
/// line (text) or byte offset (binary), for any fault: truncation, trailing bytes, NaN or infinite coordinates, indices
/// out of range, faces of fewer than 3 corners, counts larger than the file can hold (checked before anything is
/// allocated).
[[nodiscard]] TriangleMesh load_mesh(const std::filesystem::path& path, const LoadOptions& options = {},
                                     LoadReport* report = nullptr);

/// The encoding save_mesh writes a PLY file in.
enum class PlyEncoding {
  ascii,                 ///< Text, every coordinate as its shortest decimal that reads back as the same double.
  binary_little_endian,  ///< Doubles and 32-bit indices as stored in memory on little-endian machines.
};

/// Writes `mesh` as Wavefront OBJ (".obj") or PLY (".ply"), chosen by extension, such that load_mesh without joining
/// or dropping reads back the same doubles bit for bit and the same faces. Throws MeshError on an unknown extension, a
/// non-finite coordinate, a face index out of range (nothing is written then) or a write failure.
void save_mesh(const TriangleMesh& mesh, const std::filesystem::path& path, PlyEncoding ply = PlyEncoding::ascii);

}  // namespace clothcd
