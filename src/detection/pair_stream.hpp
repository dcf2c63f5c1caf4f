#pragma once
// The detector's pair stream (internal): a candidate sink that turns the chunks the broad phase hands each thread into
// blocks of pairs (vertices, canonical sort key, positions) and gives every full block to the search's stage (the
// step's CCD, the earliest-impact bound, a distance query of one state...), then reuses it. Nothing proportional to
// the number of candidates is stored. Before each block a thread checks the cancel check and the record budget, so a
// degenerate search stops within a block per thread. What a stage keeps of the pairs is its own (record_chunks.hpp).
#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// One body as the stream reads it; the pointers stay valid during the search.
struct BodyFrames {
  const broadphase::BodyTopology* topology = nullptr;  ///< Faces and edges.
  const Vertices* start = nullptr;                     ///< Positions at the start of the step (or the state).
  const Vertices* end = nullptr;                       ///< Positions at the end of the step (or the state).
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
  /// Key of face `face_a` of `body_a` against face `face_b` of `body_b` (the pairs of a face search).
  [[nodiscard]] std::uint64_t face_face(int body_a, int face_a, int body_b, int face_b) const {
    return (face_base_[body_a] + static_cast<std::uint64_t>(face_a)) * face_base_.back() + face_base_[body_b] +
           static_cast<std::uint64_t>(face_b);
  }
  /// Key of edge `edge_a` of `body_a` against edge `edge_b` of `body_b`.
  [[nodiscard]] std::uint64_t edge_edge(int body_a, int edge_a, int body_b, int edge_b) const {
    return (edge_base_[body_a] + static_cast<std::uint64_t>(edge_a)) * edge_base_.back() + edge_base_[body_b] +
           static_cast<std::uint64_t>(edge_b);
  }

 private:
  std::vector<std::uint64_t> vertex_base_, face_base_, edge_base_;  // per body, and the total at the end
};

/// One question's work on the pairs of a search, a block at a time: vertex-face and edge-edge pairs in pair blocks,
/// or the face pairs of a face search (broadphase::SearchedPairs::FaceFace). A stage takes one of the two; the other
/// throws std::logic_error.
class PairStage {
 public:
  virtual ~PairStage() = default;
  /// Works on the pairs of `block` (it may reorder them); pair i's sort key is keys[block.tag(i)]. Called from the
  /// search's threads, several at once, each with its own block. Returns how many records it added, which count in
  /// the stream's budget.
  virtual long run(ccd::PairBlock& block, const std::uint64_t* keys);
  /// Works on `count` face pairs from `pairs`, as run() does on a block.
  virtual long run_faces(const broadphase::FaceFaceCandidate* pairs, std::size_t count);
};

/// Thrown by the stream to end a search that has found what StreamLimits::stop_at asked for (the caller catches it).
struct SearchEnded {};

/// What bounds one search of the stream.
struct StreamLimits {
  /// When set and not empty: called before each block; true throws DetectionCancelled.
  const std::function<bool()>* cancel = nullptr;
  /// Once the records of the search (the `kept` ones of begin() included) pass this, the next block throws
  /// CollisionBudgetExceeded; negative: no budget.
  long max_records = -1;
  /// Once the search has this many records, the next block throws SearchEnded (a question answered by its first
  /// records); negative: never.
  long stop_at = -1;
};

/// The pair stream (see the file comment).
class PairStream final : public broadphase::CandidateSink {
 public:
  /// A stream whose threads each hold a block of `block_pairs` pairs (see ccd::PairBlock).
  explicit PairStream(int block_pairs);

  /// Starts a search whose blocks go to `stage`: `bodies` (indexed by body id), their keys and the stage must stay
  /// valid until the search ends. `kept` records of the call are already found (a re-test's kept answer).
  void begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys, const StreamLimits& limits, PairStage& stage,
             long kept);

  /// Turns one chunk of candidates into blocks for the stage (called by the search's threads). Throws
  /// CollisionBudgetExceeded or DetectionCancelled to stop the search (see StreamLimits).
  void consume(const broadphase::CandidateSet& chunk) override;

  /// Adds the candidates of the search since the last call, by kind, and resets them.
  void take_candidate_counts(long& vertex_face, long& edge_edge, long& face_face);

  /// Forgets a search (e.g. after it threw): empty blocks, no counts.
  void discard();

 private:
  // One thread's block; its tags are the pairs' indices into `keys`.
  struct Worker {
    explicit Worker(int block_pairs) : block(block_pairs), keys(static_cast<std::size_t>(block.capacity())) {}
    ccd::PairBlock block;
    std::vector<std::uint64_t> keys;  // sort key of each pair pushed, by tag
    long vertex_face = 0, edge_edge = 0, face_face = 0;
  };

  // Throws when the search must stop: the cancel check returns true, or the records found exceed the budget.
  void check_stop() const;
  // Gives the thread's block to the stage, then empties it.
  void run_block(Worker& w);

  const std::vector<BodyFrames>* bodies_ = nullptr;
  const PairKeys* keys_ = nullptr;
  PairStage* stage_ = nullptr;
  StreamLimits limits_;
  tbb::enumerable_thread_specific<Worker> workers_;
  std::atomic<long> found_{0};  // records found by all threads (the kept ones included)
};

}  // namespace clothcd::detail
