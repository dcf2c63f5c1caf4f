#pragma once
/// @file
/// The questions of one state: which primitive pairs are within a distance, and the smallest distance. A pair is one
/// detect() covers (a vertex against a closed triangle, or two closed segments), at one set of positions.

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/ccd/pair_kind.hpp"

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

/// A pair within the asked distance, at one state.
struct Proximity {
  PairKind kind = PairKind::VertexFace;  ///< Pair kind.
  std::array<VertexRef, 4> vertices{};   ///< The four vertices, ordered as PairKind says.
  /// Distance between the two closed primitives (within kDistanceRelativeError of the exact one; 0 exactly when they
  /// touch).
  double distance = 0.0;
  /// Vertex-face: barycentric weights (w1, w2) of the closest point of the triangle (w0 = 1 - w1 - w2). Edge-edge: the
  /// parameters (s on edge a, u on edge b) of the closest points, each in [0, 1]. Rounded, not exact.
  std::array<double, 2> parameters{};
  /// Unit direction from the closest point of the second primitive to that of the first (zero when they touch).
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  DistanceType type = DistanceType::PointFace;  ///< Where the closest points lie.
};

/// What CollisionDetector::minimum_distance finds.
struct MinimumDistance {
  /// True when some pair is closer than the search's upper bound (always, without one, when there is a pair at all).
  bool found = false;
  /// The smallest distance over the pairs (within kDistanceRelativeError of the exact minimum); the upper bound when
  /// none was found.
  double distance = 0.0;
  /// With `found`: a pair with that distance (the first in detect()'s order among those reported equal).
  Proximity pair;
};

/// The kinds of closest-feature pairs (IPC Toolkit's normal collisions: vertex-vertex, edge-vertex, edge-edge,
/// face-vertex).
enum class ContactKind : std::uint8_t {
  VertexVertex,  ///< vertices[0] and vertices[1].
  VertexEdge,    ///< The vertex vertices[0] and the edge vertices[1], vertices[2].
  EdgeEdge,      ///< The edges vertices[0], vertices[1] and vertices[2], vertices[3].
  VertexFace,    ///< The vertex vertices[0] and the triangle vertices[1..3].
};

/// One pair of closest features within the distance: an entry of a barrier's active set.
struct FeatureContact {
  ContactKind kind = ContactKind::VertexFace;  ///< Which features.
  /// The features' vertices (see ContactKind; unused entries are {-1, -1}). Vertex-vertex: the smaller vertex (by
  /// body, then index) first. Vertex-edge: the edge's vertices in that order. Edge-edge: each edge's vertices in that
  /// order and the smaller edge first. Vertex-face: as the Proximity has them.
  std::array<VertexRef, 4> vertices{};
  double distance = 0.0;  ///< The features' distance (that of the first Proximity mapped to them).
};

/// The pairs of closest features of `pairs` (proximity()'s records), each once, as IPC Toolkit's NormalCollisions
/// builds its active set, so that a barrier sums each contact once: a vertex-face pair whose closest point is inside
/// the triangle is a vertex-face contact, on an edge of it a vertex-edge contact, at a vertex of it a vertex-vertex
/// contact; an edge-edge pair between the ends of both edges is an edge-edge contact, at one end of one edge a
/// vertex-edge contact, at ends of both a vertex-vertex contact. Several pairs give the same contact (a vertex near
/// an edge is near both faces of the edge and near the edges at its ends); it is listed once. Sorted by kind, then
/// vertices.
[[nodiscard]] std::vector<FeatureContact> closest_feature_contacts(const std::vector<Proximity>& pairs);

}  // namespace clothcd
