#pragma once
// The pair features of many pairs at once (compute_pair_features' batch form): lane groups of pairs of one kind
// (ccd::PairLanes, structure of arrays), each step of the per-pair code run lane by lane with the same IEEE operations
// in the same order, so that the compiler vectorizes the lane loops and the features agree bit for bit with the
// per-pair function. Internal.

#include <cstddef>

#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/culling/pair_features.hpp"
#include "support/simd_level.hpp"

namespace clothcd::learning::detail {

/// Writes the first `features` (1..kMaxPairFeatures) features of pairs[0, count) into `batch` (already sized
/// count x features): feature f of pair i at batch.values[f * count + i]. Runs the build for `level`, one of
/// cpu_simd_levels() (the results are the same at every level).
void compute_feature_blocks(const ccd::CcdQuery* pairs, std::size_t count, std::size_t features, SimdLevel level,
                            PairFeatureBatch& batch);

/// The same for the pairs of `block` (batch already sized block.size() x features), read straight from its lane
/// groups: feature f of pair i at batch.values[f * block.size() + i].
void compute_feature_blocks(const ccd::PairBlock& block, std::size_t features, SimdLevel level,
                            PairFeatureBatch& batch);

/// Whether every coordinate sum of the pair is finite: the per-pair and the block code mark pairs failing it invalid.
[[nodiscard]] bool pair_coordinates_finite(const ccd::CcdQuery& pair);

}  // namespace clothcd::learning::detail
