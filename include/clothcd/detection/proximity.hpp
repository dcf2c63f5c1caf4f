#pragma once
/// @file
/// The questions of one state: which primitive pairs are within a distance, and the smallest distance. A pair is one
/// detect() covers (a vertex against a closed triangle, or two closed segments), at one set of positions.

#include <Eigen/Dense>
#include <array>

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

}  // namespace clothcd
