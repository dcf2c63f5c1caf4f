#pragma once
// The searches restricted to a few moved vertices (internal to the broad phase; TraversalSettings::moved_vertices with
// at most one vertex in kMovedQueryShare moved): the boxes of the moved primitives query the hierarchies primitive by
// primitive instead of the hierarchies being descended against each other. Each query costs a descent to the few
// leaves the box touches, while the descent restricted to dirty nodes still tests every primitive of every dirty leaf.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "broadphase/candidates.hpp"
#include "broadphase/traversal.hpp"

namespace clothcd::broadphase::detail {

/// True when at most one flag in kMovedQueryShare of `moved` is set: the searches then take the queries below.
[[nodiscard]] bool few_moved(const std::vector<std::uint8_t>& moved);

/// The pairs of find_self_candidates on `body` that involve a vertex flagged in `moved` (one flag per vertex), by
/// queries of its hierarchy, handed to `sink` in chunks of `chunk_pairs` (a chunk may exceed it by the pairs of one
/// leaf's moved primitives). With `gap_bound`, the pairs within its value (TraversalSettings::gap_bound). Serial, on
/// the calling thread; counts its tests into `stats`.
void query_moved_self(const BodyView& body, const std::vector<std::uint8_t>& moved,
                      const std::atomic<double>* gap_bound, std::size_t chunk_pairs, CandidateSink& sink,
                      TraversalStats& stats);

/// The pairs of find_pair_candidates on `a` and `b` that involve a vertex of `a` flagged in `moved`, by queries of b's
/// hierarchy with a's moved primitives, handed to `sink` as query_moved_self does.
void query_moved_pair(const BodyView& a, const BodyView& b, const std::vector<std::uint8_t>& moved,
                      const std::atomic<double>* gap_bound, std::size_t chunk_pairs, CandidateSink& sink,
                      TraversalStats& stats);

}  // namespace clothcd::broadphase::detail
