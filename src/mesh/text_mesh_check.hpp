#pragma once
// Checks of the text mesh formats whose assimp readers repair faults silently: the OFF reader turns a negative or
// too-large vertex index into a valid one and keeps faces of fewer than three vertices, and the ASCII PLY reader pads a
// body shorter than its header declares with zero vertices. Run before assimp reads the file. Internal.

#include <filesystem>

namespace clothcd::detail {

/// For an OFF file (first token OFF): throws MeshError naming the file and the face or count when a count is not a
/// whole number, the body ends before the declared vertices and faces, a face has fewer than 3 vertices, or an index
/// is not a whole number in 0 .. vertices - 1. Other files pass.
void check_off_body(const std::filesystem::path& path);

/// For an ASCII PLY file: throws MeshError when the body holds fewer lines than the elements its header declares
/// (one line per element). Other files pass.
void check_ascii_ply_body(const std::filesystem::path& path);

}  // namespace clothcd::detail
