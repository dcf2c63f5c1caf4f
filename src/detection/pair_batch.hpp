#pragma once
// The candidate pairs of one detect() call with everything the narrow phase worked out for them, and the reuse of
// that work by the next call of the same step: with the same start positions, a pair none of whose vertices moved
// has the same swept boxes, the same filter verdict and the same CCD result, so only pairs with a moved vertex need
// searching and testing again.

#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/detection/collision.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// Candidates and, per pair (vertex-face pairs first, then edge-edge pairs), its CCD query, vertex references, filter
/// verdict (keep) and CCD result.
struct PairBatch {
  broadphase::CandidateSet candidates;         ///< The pairs.
  std::vector<ccd::CcdQuery> queries;          ///< Network mode: positions of every pair (its culler reads them).
  std::vector<std::array<VertexRef, 4>> refs;  ///< Vertices of each pair.
  std::vector<std::uint8_t> keep;              ///< 1 when the pair survived culling.
  std::vector<ccd::CcdResult> results;         ///< CCD result of each kept pair (unset where keep is 0).

  /// Number of pairs.
  [[nodiscard]] std::size_t size() const { return candidates.size(); }
  /// Resizes the per-pair arrays (all but the queries) to the candidates.
  void resize_to_candidates();
};

/// Sets moved[v] = 1 for the rows of `now` that differ bitwise from those of `before` (same shape), else 0; returns
/// how many moved.
std::size_t find_moved_rows(const Vertices& before, const Vertices& now, std::vector<std::uint8_t>& moved);

/// Fills `next` with the pairs of `previous` that have no moved cloth vertex (body 0, flags `moved`), their work
/// copied (all but the queries), followed kind by kind by the `fresh` pairs; returns the positions in `next` of the
/// fresh pairs, whose queries, verdicts and results are still to be computed.
std::vector<std::size_t> merge_unmoved(const PairBatch& previous, const std::vector<std::uint8_t>& moved,
                                       const broadphase::CandidateSet& fresh, PairBatch& next);

}  // namespace clothcd::detail
