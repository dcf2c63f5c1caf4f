#pragma once
/// @file
/// Candidate primitive pairs that the broad phase hands to the filters and the exact CCD, as flat arrays.

#include <cstdint>
#include <tuple>
#include <vector>

namespace clothcd::broadphase {

/// A vertex of body `vertex_body` against a triangle of body `face_body` (body 0 is the cloth, k >= 1 obstacle k-1).
struct VertexFaceCandidate {
  std::int32_t vertex_body = 0;  ///< Body of the vertex.
  std::int32_t vertex = 0;       ///< Vertex index in that body.
  std::int32_t face_body = 0;    ///< Body of the triangle.
  std::int32_t face = 0;         ///< Face index in that body.

  /// Lexicographic order (vertex body, vertex, face body, face): the canonical output order.
  [[nodiscard]] bool operator<(const VertexFaceCandidate& o) const {
    return std::tie(vertex_body, vertex, face_body, face) < std::tie(o.vertex_body, o.vertex, o.face_body, o.face);
  }
  /// Field-wise equality.
  [[nodiscard]] bool operator==(const VertexFaceCandidate& o) const {
    return vertex_body == o.vertex_body && vertex == o.vertex && face_body == o.face_body && face == o.face;
  }
};

/// Edge `edge_a` of body `body_a` against edge `edge_b` of body `body_b` (edge indices into BodyTopology::edges).
/// Within one body edge_a < edge_b; between bodies body_a < body_b.
struct EdgeEdgeCandidate {
  std::int32_t body_a = 0;  ///< Body of the first edge.
  std::int32_t edge_a = 0;  ///< First edge.
  std::int32_t body_b = 0;  ///< Body of the second edge.
  std::int32_t edge_b = 0;  ///< Second edge.

  /// Lexicographic order (body_a, edge_a, body_b, edge_b): the canonical output order.
  [[nodiscard]] bool operator<(const EdgeEdgeCandidate& o) const {
    return std::tie(body_a, edge_a, body_b, edge_b) < std::tie(o.body_a, o.edge_a, o.body_b, o.edge_b);
  }
  /// Field-wise equality.
  [[nodiscard]] bool operator==(const EdgeEdgeCandidate& o) const {
    return body_a == o.body_a && edge_a == o.edge_a && body_b == o.body_b && edge_b == o.edge_b;
  }
};

/// Face `face_a` of body `body_a` against face `face_b` of body `body_b`, the pairs of a search for intersecting faces
/// (SearchedPairs::FaceFace). Within one body face_a < face_b; between bodies body_a < body_b.
struct FaceFaceCandidate {
  std::int32_t body_a = 0;  ///< Body of the first face.
  std::int32_t face_a = 0;  ///< First face.
  std::int32_t body_b = 0;  ///< Body of the second face.
  std::int32_t face_b = 0;  ///< Second face.

  /// Lexicographic order (body_a, face_a, body_b, face_b): the canonical output order.
  [[nodiscard]] bool operator<(const FaceFaceCandidate& o) const {
    return std::tie(body_a, face_a, body_b, face_b) < std::tie(o.body_a, o.face_a, o.body_b, o.face_b);
  }
  /// Field-wise equality.
  [[nodiscard]] bool operator==(const FaceFaceCandidate& o) const {
    return body_a == o.body_a && face_a == o.face_a && body_b == o.body_b && face_b == o.face_b;
  }
};

/// Every candidate pair of a step, without duplicates, in canonical (sorted) order once finalized.
struct CandidateSet {
  std::vector<VertexFaceCandidate> vertex_face;  ///< Vertex-face candidates.
  std::vector<EdgeEdgeCandidate> edge_edge;      ///< Edge-edge candidates.
  std::vector<FaceFaceCandidate> face_face;      ///< Face-face candidates (only a SearchedPairs::FaceFace search).

  /// Empties the arrays, keeping their storage.
  void clear() {
    vertex_face.clear();
    edge_edge.clear();
    face_face.clear();
  }
  /// Total number of candidates.
  [[nodiscard]] std::size_t size() const { return vertex_face.size() + edge_edge.size() + face_face.size(); }
};

/// Sorts the arrays into canonical order (the hierarchies already produce no duplicates).
void sort_candidates(CandidateSet& candidates);

}  // namespace clothcd::broadphase
