#pragma once
/// @file
/// A search's candidates collected into one set, for the tests and benchmarks that want them all at once: a
/// CandidateSink that appends every chunk to a CandidateSet, and the searches of traversal.hpp run into one.

#include <mutex>

#include "broadphase/candidates.hpp"
#include "broadphase/traversal.hpp"

namespace clothcd::broadphase {

/// A CandidateSink that appends every chunk it is handed to one CandidateSet. consume() may be called from several
/// threads at once (the chunks are appended one at a time), so the collected order depends on the schedule: compare
/// collected sets after sort_candidates.
class CollectingSink final : public CandidateSink {
 public:
  /// Appends to `out`, which must outlive the sink and is not to be read or changed elsewhere during a search.
  explicit CollectingSink(CandidateSet& out) : out_(out) {}

  /// Appends `chunk` to the set.
  void consume(const CandidateSet& chunk) override;

 private:
  std::mutex mutex_;
  CandidateSet& out_;
};

/// Appends to `out` the pairs that find_self_candidates hands to a sink (through a CollectingSink): the same pairs, in
/// no particular order (see sort_candidates). Throws as find_self_candidates does.
void find_self_candidates(const BodyView& body, const TraversalSettings& settings, CandidateSet& out,
                          TraversalStats* stats = nullptr);

/// Appends to `out` the pairs that find_pair_candidates hands to a sink (through a CollectingSink): the same pairs, in
/// no particular order (see sort_candidates). Throws as find_pair_candidates does.
void find_pair_candidates(const BodyView& a, const BodyView& b, const TraversalSettings& settings, CandidateSet& out,
                          TraversalStats* stats = nullptr);

}  // namespace clothcd::broadphase
