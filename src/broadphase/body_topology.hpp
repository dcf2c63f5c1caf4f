#pragma once
/// @file
/// The primitives of one body (triangles, unique edges, referenced vertices) and which triangle owns each vertex and
/// edge, so that every vertex and edge is tested from exactly one triangle (the paper's section 3.3.2).

#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::broadphase {

/// Topology of one body, fixed for the whole simulation.
struct BodyTopology {
  int vertex_count = 0;         ///< Number of vertices of the body (rows of its position arrays).
  Faces faces;                  ///< #F x 3 triangles.
  std::vector<int> edges;       ///< Unique edges as a flat array of 2 * #E vertex indices (smaller index first).
  std::vector<int> vertex_owner;  ///< #V: the face that owns each vertex, -1 when no face uses it.
  std::vector<int> edge_owner;    ///< #E: the face that owns each edge (the first face, in face order, using it).

  /// Number of unique edges.
  [[nodiscard]] int edge_count() const { return static_cast<int>(edges.size() / 2); }
  /// Number of triangles.
  [[nodiscard]] int face_count() const { return static_cast<int>(faces.rows()); }
  /// True when face `f` uses vertex `v`.
  [[nodiscard]] bool face_has_vertex(int f, int v) const {
    return faces(f, 0) == v || faces(f, 1) == v || faces(f, 2) == v;
  }
  /// True when edges `e` and `g` share a vertex (or are the same edge).
  [[nodiscard]] bool edges_share_vertex(int e, int g) const {
    const int a0 = edges[2 * e], a1 = edges[2 * e + 1], b0 = edges[2 * g], b1 = edges[2 * g + 1];
    return a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1;
  }
};

/// Builds the topology of a body with `vertex_count` vertices and triangles `faces`: unique edges (zero-length edges
/// such as (a, a) of a degenerate face are left out) and owners (each vertex and edge goes to the first face using it).
/// Throws std::invalid_argument when `faces` is empty, `vertex_count` < 1 or an index is outside [0, vertex_count).
[[nodiscard]] BodyTopology build_body_topology(const Faces& faces, int vertex_count);

}  // namespace clothcd::broadphase
