#pragma once
/// @file
/// The triangle mesh type shared by every part of clothcd.

#include <Eigen/Dense>

namespace clothcd {

/// Vertex positions: one row per vertex, columns x, y, z (row-major, so the data is a flat xyzxyz... array).
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Triangles: one row per face, three zero-based vertex indices, counter-clockwise seen from outside.
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A triangle mesh: #V x 3 positions and #F x 3 vertex indices.
struct TriangleMesh {
  Vertices vertices;  ///< #V x 3 positions.
  Faces faces;        ///< #F x 3 indices into `vertices`.

  /// Number of vertices.
  [[nodiscard]] Eigen::Index vertex_count() const { return vertices.rows(); }
  /// Number of triangles.
  [[nodiscard]] Eigen::Index face_count() const { return faces.rows(); }
};

}  // namespace clothcd
