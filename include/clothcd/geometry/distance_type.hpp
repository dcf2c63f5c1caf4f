#pragma once
/// @file
/// Where the closest points of a primitive pair lie (DistanceType), and the accuracy of a reported distance: the
/// records of the state queries (clothcd/detection/proximity.hpp) and the geometry's pair distances share them.

#include <cstdint>

namespace clothcd {

/// Where the closest points of a pair lie on its two primitives. Vertex-face pairs: vertices[0] is the point, the
/// triangle is vertices[1..3] and its edge k joins vertices[1 + k] and vertices[1 + (k + 1) % 3]. Edge-edge pairs:
/// edge a is vertices[0..1], edge b vertices[2..3]. A closest point at an end of an edge is at that vertex; one on an
/// edge of the triangle but at neither end is on that edge; otherwise it is inside.
enum class DistanceType : std::uint8_t {
  PointFace,        ///< Vertex-face: the closest point is inside the triangle.
  PointEdge0,       ///< Vertex-face: on the triangle's edge 0 (vertices[1], vertices[2]), between its ends.
  PointEdge1,       ///< Vertex-face: on edge 1 (vertices[2], vertices[3]).
  PointEdge2,       ///< Vertex-face: on edge 2 (vertices[3], vertices[1]).
  PointVertex0,     ///< Vertex-face: at the triangle's vertex vertices[1].
  PointVertex1,     ///< Vertex-face: at vertices[2].
  PointVertex2,     ///< Vertex-face: at vertices[3].
  EdgeEdge,         ///< Edge-edge: between the ends of both edges.
  EdgeVertexB0,     ///< Edge-edge: between the ends of edge a, at vertices[2].
  EdgeVertexB1,     ///< Edge-edge: between the ends of edge a, at vertices[3].
  VertexA0Edge,     ///< Edge-edge: at vertices[0], between the ends of edge b.
  VertexA1Edge,     ///< Edge-edge: at vertices[1], between the ends of edge b.
  VertexA0VertexB0, ///< Edge-edge: at vertices[0] and vertices[2].
  VertexA0VertexB1, ///< Edge-edge: at vertices[0] and vertices[3].
  VertexA1VertexB0, ///< Edge-edge: at vertices[1] and vertices[2].
  VertexA1VertexB1, ///< Edge-edge: at vertices[1] and vertices[3].
};

/// Largest relative error of a reported distance: |distance - exact| <= kDistanceRelativeError * exact, where exact is
/// the distance of the pair on the double coordinates given.
inline constexpr double kDistanceRelativeError = 0x1p-40;

}  // namespace clothcd
