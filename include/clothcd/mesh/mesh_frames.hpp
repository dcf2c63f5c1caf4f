#pragma once
/// @file
/// Reading two frames of one deformable mesh (a step's start and end) with one vertex numbering, for continuous
/// collision detection between them.

#include <filesystem>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// One mesh at two instants: vertex i of `start` and row i of `end` are the same point of the surface.
struct MeshFrames {
  TriangleMesh start;  ///< Positions at the start of the step, and the faces.
  Vertices end;        ///< Positions at the end of the step (as many rows as start.vertices).
};

/// Reads two files that hold the same mesh (same vertices in the same order, same faces) at two instants, in any
/// format load_mesh reads; every vertex and face is kept as stored (nothing joined or dropped), with the file's
/// numbering and, for OBJ, PLY, OFF and STL, the file's doubles bit for bit. STL, which gives every triangle corners
/// of its own, is the exception: when both files are STL, corners at bit-identical positions in both frames are
/// welded into one vertex. Throws MeshError naming the second file when the vertex counts or the faces differ.
[[nodiscard]] MeshFrames load_mesh_frames(const std::filesystem::path& start, const std::filesystem::path& end);

}  // namespace clothcd
