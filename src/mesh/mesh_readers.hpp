#pragma once
// The project's own readers of OBJ, PLY, OFF and STL: they keep the file's coordinates as doubles bit for bit, check
// every count against the file's size before allocating, and throw one MeshError naming the file and the line (text)
// or byte offset (binary) for anything malformed: truncation, trailing bytes, NaN or infinite coordinates, indices
// outside the vertices, faces of fewer than three corners. Polygons are split into a fan of triangles from their
// first corner. Nothing is joined or dropped here (see load_mesh). Internal.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// Wavefront OBJ: `v` lines (the first three numbers), `f` lines (`v`, `v/vt`, `v//vn`, `v/vt/vn` corners, negative
/// numbers counted back from the last vertex so far); every other line (vt, vn, o, g, usemtl, l, comments) is ignored.
[[nodiscard]] TriangleMesh read_obj(std::string_view text, const std::string& file);

/// PLY, ASCII or binary of either byte order: the vertex element's x, y, z and the face element's vertex_indices (or
/// vertex_index) list, of any scalar types; other properties and elements are skipped.
[[nodiscard]] TriangleMesh read_ply(std::string_view bytes, const std::string& file);

/// OFF (also COFF, NOFF, STOFF and their combinations): counts of vertices, faces and optionally edges, one vertex and
/// one face per line, # comments.
[[nodiscard]] TriangleMesh read_off(std::string_view text, const std::string& file);

/// STL, ASCII or binary (binary when the size matches its triangle count): three vertices of its own per triangle.
[[nodiscard]] TriangleMesh read_stl(std::string_view bytes, const std::string& file);

/// The extension of `path` in lower case, with its dot (".ply"); empty when it has none.
[[nodiscard]] std::string lower_extension(const std::filesystem::path& path);

/// Reads a file of any other format assimp knows by `extension` (lower case, with the dot), triangulating polygons and
/// applying node transforms, and stores the number of meshes it held in `source_meshes`. Coordinates pass through
/// assimp's float. Throws MeshError for an extension assimp has no reader for (it is never asked to guess from the
/// contents), an ASE file not starting with *3DSMAX_ASCIIEXPORT, a file assimp cannot read or that has no triangle.
[[nodiscard]] TriangleMesh read_with_assimp(const std::filesystem::path& path, const std::string& extension,
                                            int& source_meshes);

/// Collects a reader's positions and triangles, then makes the mesh.
struct MeshBuilder {
  std::vector<double> positions;  ///< x, y, z of every vertex in file order.
  std::vector<int> triangles;     ///< Three vertex indices per triangle.

  /// Appends the fan (c0, c1, c2), (c0, c2, c3), ... of a polygon of `count` >= 3 corners.
  void add_polygon(const int* corners, std::size_t count) {
    for (std::size_t k = 1; k + 1 < count; ++k) triangles.insert(triangles.end(), {corners[0], corners[k], corners[k + 1]});
  }
  /// The mesh of everything appended.
  [[nodiscard]] TriangleMesh finish() const {
    TriangleMesh mesh;
    mesh.vertices = Eigen::Map<const Vertices>(positions.data(), static_cast<Eigen::Index>(positions.size() / 3), 3);
    mesh.faces = Eigen::Map<const Faces>(triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
    return mesh;
  }
};

}  // namespace clothcd::detail
