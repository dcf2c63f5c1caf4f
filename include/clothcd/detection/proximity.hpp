#pragma once
/// @file
/// The questions of one state: which primitive pairs are within a distance, and the smallest distance. A pair is one
/// detect() covers (a vertex against a closed triangle, or two closed segments), at one set of positions.

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/ccd/pair_kind.hpp"
#include "clothcd/geometry/distance_type.hpp"

namespace clothcd {

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
