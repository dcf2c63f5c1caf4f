#pragma once
// The stages of the pair stream that answer the distance questions of one state (internal): every pair within a
// distance (ProximityStage), and the smallest distance (MinimumDistanceStage). A state is a step of zero length: the
// blocks hold the same positions at both ends, and the stages read the start.
#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstdint>

#include "block_culling.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/detection/proximity.hpp"
#include "pair_stream.hpp"
#include "record_chunks.hpp"

namespace clothcd::detail {

/// A pair within a distance and its sort key.
using KeyedProximity = Keyed<Proximity>;

/// Every pair of the stream within a distance (exact membership: geometry/pair_distance.hpp), kept per thread.
class ProximityStage final : public PairStage {
 public:
  /// Starts a search for the pairs closer than `distance` (> 0, finite); `edge_edge_offset` is the search's
  /// PairKeys::vertex_face_key_count(), added to the edge-edge keys.
  void begin(double distance, std::uint64_t edge_edge_offset);
  /// Tests one block (see PairStage::run); returns the pairs within the distance.
  long run(ccd::PairBlock& block, const std::uint64_t* keys) override;

  /// Adds the search's counts to `counts` and resets them.
  void take_counts(StageCounts& counts);
  /// How many pairs the search found.
  [[nodiscard]] std::size_t record_count() const;
  /// Hands the pairs found since begin() to `take(const std::vector<KeyedProximity>&)`, chunk by chunk in no
  /// particular order, freeing each chunk after it.
  template <class Take>
  void take_records(const Take& take) {
    for (Worker& w : workers_) w.records.take(take);
  }
  /// Frees what a search left, e.g. after it threw.
  void discard();

 private:
  struct Worker {
    RecordChunks<Proximity> records;
    StageCounts counts;
  };
  double distance_ = 0.0;
  std::uint64_t edge_edge_offset_ = 0;
  tbb::enumerable_thread_specific<Worker> workers_;
};

/// The pair of the stream with the smallest distance. Every pair's distance is measured; the smallest so far (each
/// thread's, and the search's as a bound the candidate search prunes by) falls as the search goes.
class MinimumDistanceStage final : public PairStage {
 public:
  /// Starts a search for the pairs closer than `upper_bound` (> 0; infinity: no bound); `edge_edge_offset` is the
  /// search's PairKeys::vertex_face_key_count(), added to the edge-edge keys for the order of ties.
  void begin(double upper_bound, std::uint64_t edge_edge_offset);
  /// Measures one block (see PairStage::run); returns 0 (the search keeps one pair, not records).
  long run(ccd::PairBlock& block, const std::uint64_t* keys) override;

  /// What the candidate search must keep: pairs whose boxes are within this of each other along every axis. Above
  /// the smallest distance found so far by its relative error, so that no pair whose reported distance could reach
  /// that one is pruned (broadphase::TraversalSettings' gap bound).
  [[nodiscard]] const std::atomic<double>& search_bound() const { return search_bound_; }
  /// The search's closest pair (distance, then kind with vertex-face first, then key); its distance is the upper bound
  /// when no pair was closer than that.
  [[nodiscard]] KeyedProximity closest() const;
  /// Adds the search's counts to `counts` and resets them.
  void take_counts(StageCounts& counts);
  /// Forgets the pairs and counts of a search.
  void discard();

 private:
  struct Worker {
    Worker();
    KeyedProximity closest;  // this thread's closest pair (distance infinity: none yet)
    StageCounts counts;
  };
  // Lowers the search's bound to the one that a pair at `distance` sets.
  void lower_bound_to(double distance);

  double upper_bound_ = 0.0;
  std::uint64_t edge_edge_offset_ = 0;
  tbb::enumerable_thread_specific<Worker> workers_;
  std::atomic<double> search_bound_{0.0};
};

}  // namespace clothcd::detail
