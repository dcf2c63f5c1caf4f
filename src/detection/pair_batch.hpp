#pragma once
// The candidate pairs of one detect() call with everything the narrow phase worked out for them, and the reuse of
// that work by the next call of the same step: with the same start positions, a pair none of whose vertices moved
// has the same swept boxes, the same filter verdict and the same CCD result, so only pairs with a moved vertex need
// searching and testing again. Their places are taken by the newly found pairs in place, so a call that moved a few
// vertices touches a few pairs, not the whole batch.

#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/detection/collision.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// A candidate of either kind: a vertex-face candidate's fields (vertex body, vertex, face body, face) or an edge-edge
/// candidate's (body a, edge a, body b, edge b).
struct BatchPair {
  PairKind kind = PairKind::VertexFace;  ///< Pair kind.
  std::array<std::int32_t, 4> fields{};  ///< The candidate's four fields in declaration order.
};

/// The pairs of a call, in no particular order, and per pair its CCD query (network mode), vertex references, filter
/// verdict (keep) and CCD result.
struct PairBatch {
  std::vector<BatchPair> pairs;                ///< The pairs.
  std::vector<ccd::CcdQuery> queries;          ///< Network mode: positions of every pair (its culler reads them).
  std::vector<std::array<VertexRef, 4>> refs;  ///< Vertices of each pair (set by the narrow phase).
  std::vector<std::uint8_t> keep;              ///< 1 when the pair survived culling.
  std::vector<ccd::CcdResult> results;         ///< CCD result of each kept pair (unset where keep is 0).

  /// Number of pairs.
  [[nodiscard]] std::size_t size() const { return pairs.size(); }
  /// Makes the batch exactly `fresh` (vertex-face pairs first) and sets `all` to every position, in order.
  void assign(const broadphase::CandidateSet& fresh, std::vector<std::size_t>& all);
};

/// Sets moved[v] = 1 for the rows of `now` that differ bitwise from those of `before` (same shape), else 0; returns
/// how many moved.
std::size_t find_moved_rows(const Vertices& before, const Vertices& now, std::vector<std::uint8_t>& moved);

/// Replaces, in place, the pairs of `batch` that have a moved cloth vertex (body 0, flags `moved`) by the `fresh`
/// pairs: the fresh ones take their places (and new places at the end), the places left over are filled from the end.
/// The other pairs keep their work. Returns the positions of the fresh pairs, vertex-face ones first: their
/// references, verdicts and results are still to be computed.
std::vector<std::size_t> replace_moved(PairBatch& batch, const std::vector<std::uint8_t>& moved,
                                       const broadphase::CandidateSet& fresh);

}  // namespace clothcd::detail
