#pragma once
// The projection filter (filters.cpp) on a block of pairs of one kind at a time, in structure-of-arrays layout and
// without branches, so that the compiler runs several pairs per instruction. Internal to the library.
#include <cstdint>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "support/simd_level.hpp"

namespace clothcd::ccd::detail {

/// The in-plane directions of ProjectionFilterOptions::use_primitive_normals on one pair (the last directions the
/// per-pair filter tries; the block filter computes the same directions on its lanes): true when one of them
/// separates the primitives by more than the thickness over the whole step.
[[nodiscard]] bool separated_in_plane(const CcdQuery& query, const CcdSettings& settings);

/// The directions one call of projection_filter_block tries. The primitives' normals cull most pairs a broad phase
/// passes, so a caller with many pairs can try them alone first and the other directions on the survivors only.
enum class BlockPass {
  All,           ///< Every direction the options name.
  Normals,       ///< Only the primitives' normals at t = 0 and t = 1 (none without use_primitive_normals).
  AfterNormals,  ///< Every direction the options name except those of the Normals pass.
};

/// culled[i] = 1 for each lane i < block.count that the projection filter culls, 0 otherwise. The same test as
/// projection_filter_culls(query, settings, options) with a coarser rounding bound (16 u |s|_1 max|coordinate| per
/// projection instead of 8 u per difference; both far below the thickness at cloth scales): a pair is culled only
/// when, along one direction s, every point of one primitive lies more than thickness |s| beyond every point of the
/// other at t = 0 and at t = 1. Pairs with a coordinate beyond 1e100 in magnitude or not a number are never culled.
/// With primitive normals, the in-plane directions too (those of separated_in_plane), on every lane. With `pass`, only
/// some of the directions (a lane is culled by All exactly when Normals or AfterNormals culls it).
/// Runs the version compiled for `level`, one of cpu_simd_levels(); every level gives the same verdicts (the same IEEE
/// operations in the same order, never fused).
void projection_filter_block(const PairLanes& block, const CcdSettings& settings,
                             const ProjectionFilterOptions& options, std::uint8_t* culled,
                             SimdLevel level = simd_level(), BlockPass pass = BlockPass::All);

/// The block filter over a vector of queries of any kinds (blocks formed in order; with primitive normals, the Normals
/// pass over all, then AfterNormals over the survivors, as the detector runs it): culled[i] for queries[i]. For tests
/// and benchmarks; the detector fills its blocks straight from the vertex arrays.
void projection_filter_queries(const std::vector<CcdQuery>& queries, const CcdSettings& settings,
                               const ProjectionFilterOptions& options, std::vector<std::uint8_t>& culled,
                               SimdLevel level = simd_level());

}  // namespace clothcd::ccd::detail
