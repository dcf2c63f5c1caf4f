#pragma once
/// @file
/// What collision detection reports: one record per colliding primitive pair.

#include <Eigen/Dense>
#include <array>
#include <cstdint>

#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd {

/// One collision found over a step [t0, t1].
struct Collision {
  PairKind kind = PairKind::VertexFace;  ///< Pair kind.
  std::array<VertexRef, 4> vertices{};   ///< The four vertices, ordered as PairKind says.
  double toi = 0.0;                      ///< Earliest time of impact as a fraction of the step, in [0, 1].
  /// VertexFace: barycentric weights of the contact point on the triangle (w1, w2; w0 = 1 - w1 - w2).
  /// EdgeEdge: the parameters (s on edge a, u on edge b) of the closest points, each in [0, 1].
  std::array<double, 2> parameters{};
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< Unit contact normal at toi, from the second primitive to the first.
  bool conservative = false;  ///< True when reported because the CCD could not decide the pair (toi: a lower bound).
};

}  // namespace clothcd
