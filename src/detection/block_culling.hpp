#pragma once
// The culling of a block of pairs before their exact test (internal), shared by the step's stages: the filters the
// detector's settings name, or its culler with the combined filters behind it (culler_stage.hpp).
#include <cstdint>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/detection/pair_culler.hpp"
#include "culler_stage.hpp"

namespace clothcd::detail {

/// How a detector culls and tests every pair of a step (fixed when the detector is made: DetectorPlan).
struct PairTestSettings {
  ccd::CcdFilter filter = ccd::CcdFilter::Combined;  ///< Culling without a culler.
  ccd::CcdSettings ccd;                              ///< Thickness and exactness.
  ccd::ProjectionFilterOptions projection;           ///< Directions of the projection filter.
  const PairCuller* culler = nullptr;                ///< When set: the culler, with the combined filters behind it.
};

/// Counts and thread times of a search's pairs (times summed over threads).
struct StageCounts {
  long vertex_face = 0;   ///< Vertex-face candidates.
  long edge_edge = 0;     ///< Edge-edge candidates.
  long face_face = 0;     ///< Face-face candidates (a face search).
  long culled = 0;        ///< Candidates the culling removed.
  CullerCounts culler;    ///< Network mode: the culler's verdicts and the filters behind it.
  double culling_ms = 0;  ///< Culling, the culler's part included.
  double exact_ms = 0;    ///< Exact tests.

  /// Adds the counts and times of `o`.
  void add(const StageCounts& o);
};

/// A thread's scratch for cull_block (grown as needed, then reused).
struct CullScratch {
  std::vector<std::uint8_t> culled;  ///< The block filters' scratch.
  CullerScratch culler;              ///< Network mode: cull_with_culler's scratch.
};

/// Where the survivors of cull_block stand in the block.
struct BlockSurvivors {
  int filtered = 0;   ///< Pairs [0, filtered) passed the filters `applied` (their tests need not be repeated).
  int survivors = 0;  ///< Pairs [filtered, survivors): the culler's Keep pairs, which met no filter.
  ccd::CcdFilter applied = ccd::CcdFilter::None;  ///< The filters the first survivors passed.
};

/// Culls the pairs of `block` by `settings` and moves the survivors to its front; adds the culled pairs, the culler's
/// counts and the time to `counts`.
BlockSurvivors cull_block(ccd::PairBlock& block, const PairTestSettings& settings, CullScratch& scratch,
                          StageCounts& counts);

}  // namespace clothcd::detail
