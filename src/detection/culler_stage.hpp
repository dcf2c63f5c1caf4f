#pragma once
// The detector's culling stage of CullingMode::Network (internal): a PairCuller's verdicts on a block, confirmed by the
// combined block filters (see the safety contract in clothcd/detection/pair_culler.hpp).
#include <cstdint>
#include <memory>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/detection/pair_culler.hpp"

namespace clothcd {

/// Counts and times of culling blocks with a PairCuller (cull_with_culler).
struct CullerCounts {
  long dropped = 0;        ///< Drops the combined filters confirmed (removed).
  long overruled = 0;      ///< Drops the combined filters did not confirm (sent to the exact test).
  long checked = 0;        ///< Check verdicts (sent through the combined filters).
  long filter_culled = 0;  ///< Check pairs the combined filters removed.
  long kept = 0;           ///< Keep verdicts (straight to the exact test).
  double culler_ms = 0;    ///< Time in PairCuller::cull.
  double filters_ms = 0;   ///< Time in the combined filters behind it.

  /// Adds the counts and times of `o`.
  void add(const CullerCounts& o);
};

/// A thread's scratch for cull_with_culler (grown as needed, then reused).
struct CullerScratch {
  std::unique_ptr<PairCuller::Scratch> culler;  ///< The culler's own, made on first use.
  std::vector<CullVerdict> verdicts;            ///< The culler's verdicts on the block.
  std::vector<std::uint8_t> culled;             ///< The block filters' scratch.
};

/// Where the survivors of cull_with_culler stand in the block.
struct CullerSurvivors {
  int filtered = 0;  ///< Pairs [0, filtered): passed the combined filters (unconfirmed drops and Check pairs).
  int kept = 0;      ///< Pairs [filtered, filtered + kept): Keep verdicts, not filtered.
};

/// Network mode's culling of a whole block: `culler` gives its verdicts, the combined block filters
/// (ccd::cull_pair_block with `settings` and `projection`) confirm or overrule the drops and check the Check pairs, and
/// the survivors are moved to the front of the block (filtered ones first, then the Keep ones; the order within the
/// block changes). Adds to `counts`.
CullerSurvivors cull_with_culler(const PairCuller& culler, ccd::PairBlock& block, const ccd::CcdSettings& settings,
                                 const ccd::ProjectionFilterOptions& projection, CullerScratch& scratch,
                                 CullerCounts& counts);

}  // namespace clothcd
