#pragma once
// cull_pair_block on a chosen instruction set (internal: the tests compare every supported one).
#include <cstdint>
#include <vector>

#include "ccd/projection_block.hpp"
#include "clothcd/ccd/pair_block.hpp"

namespace clothcd::ccd::detail {

/// cull_pair_block with the block filters run at `level` (one of cpu_simd_levels()).
int cull_pairs(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
               const ProjectionFilterOptions& options, SimdLevel level, std::vector<std::uint8_t>& culled);

}  // namespace clothcd::ccd::detail
