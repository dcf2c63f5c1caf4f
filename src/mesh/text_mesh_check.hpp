#pragma once
// Checks of the text mesh formats whose assimp readers repair faults silently: the OFF reader turns a negative or
// too-large vertex index into a valid one and keeps faces of fewer than three vertices, the ASCII PLY reader pads a
// body shorter than its header declares with zero vertices, and the binary one allocates whatever count is declared.
// Run before assimp reads the file. Internal.

#include <filesystem>
#include <vector>

namespace clothcd::detail {

/// For an OFF file (first token OFF): throws MeshError naming the file and the face or count when a count is not a
/// whole number, the body ends before the declared vertices and faces, a vertex coordinate has 20 or more integer
/// digits, a face has fewer than 3 vertices, or an index is not a whole number in 0 .. vertices - 1. Other files pass.
void check_off_body(const std::filesystem::path& path);

/// For a PLY file: throws MeshError when an element count is not a whole number, a property type is unknown, the vertex
/// element lacks an x, y or z property (the reader would put every vertex at the origin), an ASCII
/// body holds fewer lines than the elements its header declares (one line per element), a line whose values do not
/// match its element's properties (a face declaring 255 indices and giving 3 lost the faces after it) or a number of
/// 20 or more integer digits, or a binary body is shorter than the header allows (assimp's binary reader allocates the
/// declared count first: 2e9 vertices in a 300-byte file took gigabytes). Other files pass.
void check_ply_body(const std::filesystem::path& path);

/// For an ASE file: throws MeshError unless its first token is *3DSMAX_ASCIIEXPORT (assimp's ASE reader turns any text,
/// "hello world" included, into an 8-face mesh at the origin). Call only for ASE files.
void check_ase_header(const std::filesystem::path& path);

/// For an OBJ file: the vertex number of every corner of every `f` line, in file order (1-based as written; a
/// negative, relative number is resolved against the vertices read so far; 0 where a corner holds no number).
[[nodiscard]] std::vector<long long> obj_face_vertices(const std::filesystem::path& path);

/// For an OBJ file: throws MeshError naming the file and vertex when a vertex coordinate has 20 or more integer digits
/// (assimp's readers, here and in OFF and ASCII PLY, read such numbers as 0). Call only for OBJ files.
void check_obj_numbers(const std::filesystem::path& path);

}  // namespace clothcd::detail
