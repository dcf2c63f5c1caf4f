#pragma once
// The block filters of the detector's culling modes on a PairBlock (internal), on the widest instruction set the CPU has
// or on a chosen one (the tests compare every supported one).
#include <cstdint>
#include <vector>

#include "ccd/projection_block.hpp"
#include "clothcd/ccd/pair_block.hpp"

namespace clothcd::ccd {

/// The filters of the detector's culling modes on pairs [0, count) of `block`, as the block filters run them: the
/// projection filter (with primitive normals: their pass on every pair first, the other directions on the survivors)
/// and, in the Combined mode at thickness 0, the non-penetration filter on what the projection filter leaves;
/// NonPenetration runs the per-pair filter, None culls nothing. The survivors are compacted to the front of the block
/// (PairBlock::compact); returns how many. `culled` is scratch (resized as needed). The
/// filters run on the widest instruction set the CPU has; every one gives the same verdicts.
int cull_pair_block(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
                    const ProjectionFilterOptions& options, std::vector<std::uint8_t>& culled);

namespace detail {

/// cull_pair_block with the block filters run at `level` (one of cpu_simd_levels()).
int cull_pairs(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
               const ProjectionFilterOptions& options, SimdLevel level, std::vector<std::uint8_t>& culled);

}  // namespace detail

}  // namespace clothcd::ccd
