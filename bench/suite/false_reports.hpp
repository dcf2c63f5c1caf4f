#pragma once
/// @file
/// Which reported collisions of a step do not collide: each reported pair's CcdQuery, built from the step's two
/// frames, decided by the exact rational reference (ccd::exact_collision_reference, GMP).

#include <cstddef>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "detect_run.hpp"

namespace clothcd::bench {

/// The query of the collision `key` (detect_run.hpp's form) between the two frames: vertex-face {vertex, face} gives
/// {vertex, the face's three corners}; edge-edge {a0, a1, b0, b1} gives those four vertices. Throws std::out_of_range
/// when an index is outside the mesh.
[[nodiscard]] ccd::CcdQuery collision_query(const MeshFrames& frames, const CollisionKey& key);

/// The outcome of checking reported collisions against the exact reference.
struct FalseReportCheck {
  long reported = 0;       ///< Collisions given.
  long checked = 0;        ///< Of those, decided by the reference (all, or an evenly spaced sample).
  long not_colliding = 0;  ///< Of those checked, the reference says do not touch during the step.
  double ms = 0;           ///< Time the reference took.

  /// Every reported collision was checked.
  [[nodiscard]] bool complete() const { return checked == reported; }
};

/// Decides `reported` with the exact reference: every one when there are at most `limit`, else `limit` of them evenly
/// spaced in the given order (limit 0: none).
[[nodiscard]] FalseReportCheck check_false_reports(const MeshFrames& frames, const std::vector<CollisionKey>& reported,
                                                   std::size_t limit);

}  // namespace clothcd::bench
