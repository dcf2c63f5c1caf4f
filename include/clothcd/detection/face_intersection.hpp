#pragma once
/// @file
/// The third question of one state: which pairs of closed triangles intersect. Two faces intersect when they share a
/// point (touching counts). Faces of one body that share a vertex or an edge intersect only where they meet beyond
/// it: faces sharing an edge when they overlap in their common plane beyond the edge, faces sharing one vertex when a
/// point other than that vertex is common to both (the semantics of CGAL's Polygon_mesh_processing::self_intersections).

#include <array>
#include <cstdint>

#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd {

/// One intersecting face pair.
struct FaceIntersection {
  std::array<std::int32_t, 2> bodies{};  ///< Body of each face (0 = cloth; bodies[0] <= bodies[1]).
  /// Face index of each in its body (within one body faces[0] < faces[1]).
  std::array<std::int32_t, 2> faces{};
  /// A point common to both faces where an edge of one meets the other, so that untangling can start from it:
  /// which face the edge belongs to (0 or 1), the edge's two vertices (in the face's order), the parameter s of the
  /// point on the edge (from edge[0] to edge[1], in [0, 1]) and its barycentric weights (w1, w2) on the other face:
  /// the weights of that face's corners 1 and 2 (in its vertex order), its corner 0 weighing 1 - w1 - w2. Rounded,
  /// not exact; the intersection itself is decided exactly.
  int edge_face = 0;
  std::array<VertexRef, 2> edge{};       ///< The crossing edge's vertices.
  double edge_parameter = 0.0;           ///< s on the edge.
  std::array<double, 2> face_weights{};  ///< (w1, w2): the weights of the other face's corners 1 and 2.
  bool coplanar = false;                 ///< The two faces lie in one plane (exactly).
};

}  // namespace clothcd
