#pragma once
// What a detector's settings mean for its work (internal), worked out once when the detector is made: the checked
// settings, the culling and exact test of every pair (filters, culler, CCD settings), the hierarchies' build settings
// from the hierarchy kind, and the candidate search's settings. Every search reads it; none translates the settings
// again.
#include <memory>

#include "broadphase/bvh.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/detection/pair_culler.hpp"
#include "block_culling.hpp"

namespace clothcd::detail {

/// A detector's settings, checked and turned into the settings of its parts.
struct DetectorPlan {
  /// Checks `settings` (std::invalid_argument naming the setting at fault) and derives the rest from them.
  explicit DetectorPlan(const DetectorSettings& settings);

  DetectorSettings settings;                 ///< As given.
  std::shared_ptr<const PairCuller> culler;  ///< CullingMode::Network's culler (null in every other mode).
  PairTestSettings pair_tests;               ///< The culling and the exact test of every pair.
  broadphase::BvhSettings cloth_hierarchy;   ///< The cloth's hierarchy.
  broadphase::VolumeKind obstacle_volume;    ///< The obstacles' node volume (their other settings are the cloth's).
  /// The candidate search (TraversalSettings::moved_vertices is set per search).
  broadphase::TraversalSettings traversal;
};

}  // namespace clothcd::detail
