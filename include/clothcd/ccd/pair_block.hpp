#pragma once
/// @file
/// The pairs of the CCD stage in blocks, as a PairCuller and a BlockObserver see them: a fixed-capacity block of pairs
/// of one kind on their way from the broad phase to the exact test, holding each pair's four vertex references, a tag
/// the caller chooses and its start and end positions as lanes of PairLanes groups (structure of arrays), so that the
/// block filters read them in place. A detector fills a block, culls it, runs the exact test on the survivors
/// (continuous_collision_after_filter on query(i)) and reuses it, so the pairs of a step are never all held at once.
#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd::ccd {

/// Positions of up to kLanes pairs of one kind, one lane group of a PairBlock and the block filters' unit:
/// x[time][point][axis][lane], time 0 = start, 1 = end, points in CcdQuery order. The filter computes on every lane;
/// lanes at or beyond `count` must hold copies (pad_unused()).
struct PairLanes {
  static constexpr int kLanes = 16;  ///< Pairs per block.
  PairKind kind = PairKind::VertexFace;  ///< Kind of every pair of the block.
  int count = 0;                         ///< Pairs in use (lanes 0 .. count - 1).
  alignas(64) double x[2][4][3][kLanes];  ///< Coordinates (left uninitialised: filled lane by lane).

  /// Stores `query`'s positions in lane `lane` (the kind is the block's).
  void set(int lane, const CcdQuery& query);
  /// The query of lane `lane`.
  [[nodiscard]] CcdQuery query(int lane) const;
  /// Copies lane 0 (count >= 1) into the lanes from count on.
  void pad_unused();
};

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
    PairLanes& group = groups_[static_cast<std::size_t>(i / PairLanes::kLanes)];
    const int lane = i % PairLanes::kLanes;
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
    return groups_[static_cast<std::size_t>(i / PairLanes::kLanes)].query(i % PairLanes::kLanes);
  }
  /// Lane group g: pairs g kLanes .. g kLanes + kLanes - 1 (those at or past size() hold earlier pairs' or zero
  /// coordinates).
  [[nodiscard]] const PairLanes& group(int g) const { return groups_[static_cast<std::size_t>(g)]; }

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
  std::vector<PairLanes> groups_;
};

}  // namespace clothcd::ccd
