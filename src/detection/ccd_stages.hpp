#pragma once
// The two stages of the pair stream that answer the questions of a step (internal): every collision of the step
// (StepCollisionStage), and the earliest contact (EarliestImpactStage). Both cull a block first (block_culling.hpp)
// and run the exact CCD on its survivors while they are in cache.
#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "block_culling.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/detection/block_observer.hpp"
#include "clothcd/detection/collision.hpp"
#include "pair_stream.hpp"
#include "record_chunks.hpp"

namespace clothcd::detail {

/// A collision and its sort key.
using KeyedCollision = Keyed<Collision>;

/// True when `a` comes before `b` in the earliest-impact order: time of impact, then kind (vertex-face first), then key
/// (the order of detect()'s list).
[[nodiscard]] bool earlier_impact(const KeyedCollision& a, const KeyedCollision& b);

/// Every collision of a step: the culling, then the exact CCD of each survivor, keeping the collisions per thread.
class StepCollisionStage final : public PairStage {
 public:
  /// A stage with `settings` (kept by reference: they must outlive it).
  explicit StepCollisionStage(const PairTestSettings& settings);

  /// Starts a search. `test` false only culls (the counts of a search, no exact test and no collisions); with
  /// `observer`, every block is shown to it after its exact test; `edge_edge_offset` is the search's
  /// PairKeys::vertex_face_key_count(), added to the edge-edge keys.
  void begin(bool test, const BlockObserver* observer, std::uint64_t edge_edge_offset);
  /// Culls and tests one block (see PairStage::run); returns the collisions found.
  long run(ccd::PairBlock& block, const std::uint64_t* keys) override;

  /// Adds the search's counts to `counts` and resets them.
  void take_counts(StageCounts& counts);
  /// How many collisions the search found.
  [[nodiscard]] std::size_t record_count() const;
  /// Hands the collisions found since begin() to `take(const std::vector<KeyedCollision>&)`, chunk by chunk in no
  /// particular order, freeing each chunk after it.
  template <class Take>
  void take_records(const Take& take) {
    for (Worker& w : workers_) w.collisions.take(take);
  }
  /// Frees what a search left (its collisions and counts), e.g. after it threw.
  void discard();

 private:
  struct Worker {
    CullScratch scratch;
    std::unique_ptr<ccd::PairBlock> observed;                       // with an observer: the block before culling
    std::vector<std::uint8_t> observed_culled, observed_colliding;  // with an observer: per pair, by tag
    RecordChunks<Collision> collisions;
    StageCounts counts;
  };
  void show_block(Worker& w, const ccd::PairBlock& block, const std::uint64_t* keys, int survivors) const;

  const PairTestSettings& settings_;
  bool test_ = true;
  const BlockObserver* observer_ = nullptr;
  std::uint64_t edge_edge_offset_ = 0;
  tbb::enumerable_thread_specific<Worker> workers_;
};

/// The earliest contact of a window of a step: the culling, then each survivor's exact CCD up to the earliest time of
/// impact found so far by any thread, or the window's end when that is earlier (ccd::continuous_collision_until). No
/// collision is kept; each thread keeps its earliest hit. The pairs that collide within that bound count as records
/// (in the budget): a degenerate step (all of a collapsing cloth touching at the end) stops as detect() does.
class EarliestImpactStage final : public PairStage {
 public:
  /// A stage with `settings` (kept by reference: they must outlive it).
  explicit EarliestImpactStage(const PairTestSettings& settings);

  /// Starts a search of the window ending at `window` (pairs are tested up to it), with `earliest_bound` a time of
  /// impact found before (an earlier window's; infinity when none); `edge_edge_offset` is the search's
  /// PairKeys::vertex_face_key_count(), added to the edge-edge keys.
  void begin(double window, double earliest_bound, std::uint64_t edge_edge_offset);
  /// Culls and tests one block (see PairStage::run); returns the pairs that collide within the bound.
  long run(ccd::PairBlock& block, const std::uint64_t* keys) override;

  /// The search's earliest hit, ties broken by kind (vertex-face first) and key (edge-edge keys after every
  /// vertex-face key); toi infinity when the search found none at or before its bound.
  [[nodiscard]] KeyedCollision earliest() const;
  /// Adds the search's counts to `counts` and resets them.
  void take_counts(StageCounts& counts);
  /// Forgets the hits and counts of a search.
  void discard();

 private:
  struct Worker {
    Worker() { earliest.record.toi = std::numeric_limits<double>::infinity(); }
    CullScratch scratch;
    KeyedCollision earliest;  // this thread's earliest hit (toi infinity: none yet)
    StageCounts counts;
  };

  const PairTestSettings& settings_;
  double window_ = 1.0;
  std::uint64_t edge_edge_offset_ = 0;
  tbb::enumerable_thread_specific<Worker> workers_;
  std::atomic<double> earliest_toi_{0.0};  // the earliest toi found so far
};

}  // namespace clothcd::detail
