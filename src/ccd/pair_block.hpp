#pragma once
// A fixed-capacity block of pairs of one kind on their way from the broad phase to the exact test (internal to the
// library): each pair's four vertex references, a tag the caller chooses and its start and end positions, stored as
// QueryBlock lanes (structure of arrays, QueryBlock::kLanes pairs per group) so that the block filters read them in
// place. A detector fills a block, culls it, tests the survivors and reuses it, so the pairs of a step are never all
// held at once.
#include <array>
#include <cstdint>
#include <vector>

#include "ccd/projection_block.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd::ccd::detail {

/// Pairs of one kind with their vertices, tags and positions (see the file comment).
class PairBlock {
 public:
  /// An empty block for `capacity` pairs (1 .. 2^20; rounded up to whole lane groups). Every lane starts at the
  /// origin, so that lanes past the last pair always hold finite coordinates for the block filters. Throws
  /// std::invalid_argument for a capacity out of range and std::runtime_error when the block cannot be allocated.
  explicit PairBlock(int capacity);

  /// Empties the block for pairs of `kind`.
  void reset(PairKind kind);
  /// Kind of every pair.
  [[nodiscard]] PairKind kind() const { return kind_; }
  /// Pairs held.
  [[nodiscard]] int size() const { return size_; }
  /// Pairs the block can hold.
  [[nodiscard]] int capacity() const { return static_cast<int>(vertices_.size()); }
  /// True when no pair can be added.
  [[nodiscard]] bool full() const { return size_ == capacity(); }

  /// Appends a pair (the block must not be full): its vertices, its tag and the positions of its four points (in
  /// CcdQuery order) at the start and end of the step, three doubles each.
  void push(const std::array<VertexRef, 4>& vertices, std::uint64_t tag, const std::array<const double*, 4>& start,
            const std::array<const double*, 4>& end) {
    const int i = size_++;
    vertices_[static_cast<std::size_t>(i)] = vertices;
    tags_[static_cast<std::size_t>(i)] = tag;
    QueryBlock& group = groups_[static_cast<std::size_t>(i / QueryBlock::kLanes)];
    const int lane = i % QueryBlock::kLanes;
    for (int k = 0; k < 4; ++k) {
      for (int c = 0; c < 3; ++c) {
        group.x[0][k][c][lane] = start[k][c];
        group.x[1][k][c][lane] = end[k][c];
      }
    }
  }

  /// The vertices of pair i.
  [[nodiscard]] const std::array<VertexRef, 4>& vertices(int i) const { return vertices_[static_cast<std::size_t>(i)]; }
  /// The tag of pair i.
  [[nodiscard]] std::uint64_t tag(int i) const { return tags_[static_cast<std::size_t>(i)]; }
  /// The CCD query of pair i.
  [[nodiscard]] CcdQuery query(int i) const {
    return groups_[static_cast<std::size_t>(i / QueryBlock::kLanes)].query(i % QueryBlock::kLanes);
  }
  /// Lane group g: pairs g kLanes .. g kLanes + kLanes - 1 (those at or past size() hold earlier pairs' or zero
  /// coordinates).
  [[nodiscard]] const QueryBlock& group(int g) const { return groups_[static_cast<std::size_t>(g)]; }

  /// Keeps, in order, the pairs i < count with keep[i] != 0 as pairs 0, 1, ...; the pairs from `count` on move down
  /// behind them. Returns how many of the first `count` were kept.
  int compact(int count, const std::uint8_t* keep);
  /// Exchanges pairs i and j.
  void swap_pairs(int i, int j);

 private:
  void copy_pair(int from, int to);

  PairKind kind_ = PairKind::VertexFace;
  int size_ = 0;
  std::vector<std::array<VertexRef, 4>> vertices_;
  std::vector<std::uint64_t> tags_;
  std::vector<QueryBlock> groups_;
};

/// The filters of the detector's culling modes on pairs [0, count) of `block`, as the block filters run them: the
/// projection filter (with primitive normals: their pass on every pair first, the other directions on the survivors)
/// and, in the Combined mode at thickness 0, the non-penetration filter on what the projection filter leaves;
/// NonPenetration runs the per-pair filter, None culls nothing. The survivors are compacted to the front of the block
/// (PairBlock::compact); returns how many. `culled` is scratch of at least `count` entries.
int cull_pairs(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
               const ProjectionFilterOptions& options, BlockIsa isa, std::vector<std::uint8_t>& culled);

}  // namespace clothcd::ccd::detail
