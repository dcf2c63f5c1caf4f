#pragma once
// The detector's narrow phase as a candidate sink (internal): each thread turns the candidate chunks the broad phase
// hands it into pair blocks (vertices, canonical sort key, positions), culls a block (the filters, or a culler with
// the filters behind it), runs the exact test on the survivors while they are in cache, keeps only the
// collisions and reuses the block. Nothing proportional to the number of candidates is stored; the collisions are kept
// in chunks of fixed size (no vector doubling: the memory is the collisions' own), and between blocks each thread
// checks the collision budget and the cancel check, so that a degenerate step stops within a block per thread.
#include <tbb/enumerable_thread_specific.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/traversal.hpp"
#include "ccd/pair_block.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/detection/block_observer.hpp"
#include "clothcd/detection/collision.hpp"
#include "clothcd/detection/pair_culler.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"
#include "detection/culler_stage.hpp"

namespace clothcd::detail {

/// One body as the narrow phase reads it; the pointers stay valid during the search.
struct BodyFrames {
  const broadphase::BodyTopology* topology = nullptr;  ///< Faces and edges.
  const Vertices* start = nullptr;                     ///< Positions at the start of the step.
  const Vertices* end = nullptr;                       ///< Positions at the end of the step.
};

/// Canonical order of pairs by one integer key: numbering every body's vertices (faces, edges) one after the other in
/// body order maps (body, index) to a dense number with the same order, and dense first * (count of the second kind) +
/// dense second orders like the candidate's four fields (broadphase::sort_candidates' order within one kind).
class PairKeys {
 public:
  /// Numbers the primitives of `bodies` (in body order).
  void assign(const std::vector<BodyFrames>& bodies);
  /// Key of vertex `vertex` of `vertex_body` against face `face` of `face_body`.
  [[nodiscard]] std::uint64_t vertex_face(int vertex_body, int vertex, int face_body, int face) const {
    return (vertex_base_[vertex_body] + static_cast<std::uint64_t>(vertex)) * face_base_.back() +
           face_base_[face_body] + static_cast<std::uint64_t>(face);
  }
  /// One more than the largest vertex-face key: added to the edge-edge keys, it orders every vertex-face pair first.
  [[nodiscard]] std::uint64_t vertex_face_key_count() const { return vertex_base_.back() * face_base_.back(); }
  /// Key of edge `edge_a` of `body_a` against edge `edge_b` of `body_b`.
  [[nodiscard]] std::uint64_t edge_edge(int body_a, int edge_a, int body_b, int edge_b) const {
    return (edge_base_[body_a] + static_cast<std::uint64_t>(edge_a)) * edge_base_.back() + edge_base_[body_b] +
           static_cast<std::uint64_t>(edge_b);
  }

 private:
  std::vector<std::uint64_t> vertex_base_, face_base_, edge_base_;  // per body, and the total at the end
};

/// A collision and its canonical sort key (PairKeys).
struct KeyedCollision {
  std::uint64_t key = 0;  ///< Sort key within its kind.
  Collision collision;    ///< The collision.
};

/// True when `a` comes before `b` in the earliest-impact order: time of impact, then kind (vertex-face first), then key
/// (the order of detect()'s list).
[[nodiscard]] bool earlier_impact(const KeyedCollision& a, const KeyedCollision& b);

/// How the pipeline treats every pair of a detector (fixed when the detector is made: DetectorPlan).
struct PipelineSettings {
  ccd::CcdFilter filter = ccd::CcdFilter::Combined;  ///< Culling without a culler.
  ccd::CcdSettings ccd;                              ///< Thickness and exactness.
  ccd::ProjectionFilterOptions projection;           ///< Directions of the projection filter.
  const PairCuller* culler = nullptr;                ///< When set: the culler, with the combined filters behind it.
  long max_collisions = 0;  ///< With PipelineSearch::exact: the budget (CollisionBudgetExceeded beyond it).
};

/// What one search asks of the pipeline.
struct PipelineSearch {
  bool exact = true;  ///< False: only count the candidates and the culled pairs (no exact test, no collisions).
  const BlockObserver* observer = nullptr;  ///< When set: shown every block after its exact test.
  /// When set and not empty: called before each block; true throws DetectionCancelled.
  const std::function<bool()>* cancel = nullptr;
  /// With `exact`: search the earliest contact instead of every collision. Each survivor is tested only up to the
  /// earliest time of impact found so far by any thread, or `window` when that is earlier
  /// (ccd::continuous_collision_until), no collisions are kept, and each thread keeps its earliest hit
  /// (PairPipeline::earliest). The pairs that collide within that bound count in the budget: a degenerate step (all
  /// of a collapsing cloth touching at the end) stops as detect() does.
  bool earliest = false;
  double window = 1.0;  ///< With `earliest`: the end of the time window searched (pairs are tested up to it).
  /// With `earliest`: a time of impact found before this search (an earlier window's); pairs are tested up to it.
  double earliest_bound = std::numeric_limits<double>::infinity();
};

/// Counts and thread times of the pipeline (times summed over threads).
struct PipelineCounts {
  long vertex_face = 0;        ///< Vertex-face candidates.
  long edge_edge = 0;          ///< Edge-edge candidates.
  long culled = 0;             ///< Candidates the culling removed.
  CullerCounts culler;         ///< Network mode: the culler's verdicts and the filters behind it.
  double culling_ms = 0;       ///< Culling, the culler's part included.
  double exact_ms = 0;         ///< Exact tests.

  /// Adds the counts and times of `o`.
  void add(const PipelineCounts& o);
};

/// The narrow phase as a broad-phase sink (see the file comment).
class PairPipeline final : public broadphase::CandidateSink {
 public:
  /// A pipeline with `settings` whose threads each hold a block of `block_pairs` pairs (see ccd::PairBlock).
  PairPipeline(const PipelineSettings& settings, int block_pairs);

  /// Collisions each chunk of a thread's list holds (1.7 MB of them).
  static constexpr std::size_t kChunkCollisions = std::size_t{1} << 14;

  /// Starts `search`: `bodies` (indexed by body id) and their keys must stay valid until the collisions are taken.
  /// `kept` collisions of the call are already found (a re-test's kept answer): they count in the budget.
  void begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys, const PipelineSearch& search, long kept);

  /// Culls and tests one chunk of candidates (called by the search's threads). Throws CollisionBudgetExceeded or
  /// DetectionCancelled to stop the search (see PipelineSearch).
  void consume(const broadphase::CandidateSet& chunk) override;

  /// Adds the counts of the search to `counts`.
  void add_counts(PipelineCounts& counts);

  /// How many collisions the search found.
  [[nodiscard]] std::size_t collision_count() const;

  /// Hands the collisions found since begin() to `take(const std::vector<KeyedCollision>&)`, chunk by chunk in no
  /// particular order, and frees each chunk after it (so that copying them out needs no memory beyond one chunk).
  template <class Take>
  void take_collisions(const Take& take) {
    for (Worker& w : workers_) {
      for (std::vector<KeyedCollision>& chunk : w.collisions) {
        take(chunk);
        std::vector<KeyedCollision>().swap(chunk);
      }
      w.collisions.clear();
    }
  }

  /// With PipelineSearch::earliest: the search's earliest hit, ties broken by kind (vertex-face first) and key; toi
  /// beyond every hit (infinity) when the search found none at or before its bound.
  [[nodiscard]] KeyedCollision earliest() const;

  /// Frees what a search left (its collisions and counts), e.g. after it threw.
  void discard();

 private:
  // One thread's block, scratch, collisions and counts. The block's tags are the pairs' indices into `keys`.
  struct Worker {
    explicit Worker(int block_pairs) : block(block_pairs), keys(static_cast<std::size_t>(block.capacity())) {
      earliest.collision.toi = std::numeric_limits<double>::infinity();
    }
    ccd::PairBlock block;
    std::vector<std::uint64_t> keys;                      // sort key of each pair pushed, by tag
    std::unique_ptr<ccd::PairBlock> observed;             // with an observer: the block before culling
    std::vector<std::uint8_t> observed_culled, observed_colliding;  // with an observer: per pair, by tag
    std::vector<std::uint8_t> culled;                     // cull_pair_block's scratch
    CullerScratch culler;                                 // network mode: cull_with_culler's scratch
    std::vector<std::vector<KeyedCollision>> collisions;  // found, in chunks of kChunkCollisions
    KeyedCollision earliest;  // PipelineSearch::earliest: this thread's earliest hit (toi infinity: none yet)
    PipelineCounts counts;
  };

  // Appends a collision to the thread's last chunk, or to a new one when that is full.
  static KeyedCollision& add_collision(Worker& w);
  // Throws when the search must stop: the cancel check returns true, or the collisions found exceed the budget.
  void check_stop() const;

  void run_block(Worker& w) const;
  // The exact test of the block's survivors [0, survivors) for PipelineSearch::earliest.
  void find_earliest(Worker& w, int survivors, int filtered, ccd::CcdFilter applied) const;
  void show_block(Worker& w, int survivors) const;

  const std::vector<BodyFrames>* bodies_ = nullptr;
  const PairKeys* keys_ = nullptr;
  const PipelineSettings settings_;
  PipelineSearch search_;
  tbb::enumerable_thread_specific<Worker> workers_;
  mutable std::atomic<long> found_{0};  // collisions found by all threads (the kept ones included)
  mutable std::atomic<double> earliest_toi_{0.0};  // PipelineSearch::earliest: the earliest toi found so far
};

}  // namespace clothcd::detail
