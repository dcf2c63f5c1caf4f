#pragma once
// The stage of the pair stream that answers the third question of one state (internal): which face pairs intersect,
// decided exactly (geometry/triangle_intersection.hpp) on the face pairs of a face search, kept per thread.
#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <vector>

#include "block_culling.hpp"
#include "clothcd/detection/face_intersection.hpp"
#include "pair_stream.hpp"
#include "record_chunks.hpp"

namespace clothcd::detail {

/// Every intersecting pair of the stream's face pairs.
class IntersectionStage final : public PairStage {
 public:
  /// Starts a search of the faces of `bodies` (the state at their start positions), keyed by `keys`; both must stay
  /// valid until the search ends.
  void begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys);
  /// Tests `count` face pairs (see PairStage::run_faces); returns the intersecting ones.
  long run_faces(const broadphase::FaceFaceCandidate* pairs, std::size_t count) override;

  /// Adds the search's counts to `counts` and resets them.
  void take_counts(StageCounts& counts);
  /// How many intersecting pairs the search found.
  [[nodiscard]] std::size_t record_count() const;
  /// Hands the pairs found since begin() to `take(const std::vector<Keyed<FaceIntersection>>&)`, chunk by chunk in
  /// no particular order, freeing each chunk after it.
  template <class Take>
  void take_records(const Take& take) {
    for (Worker& w : workers_) w.records.take(take);
  }
  /// Frees what a search left, e.g. after it threw.
  void discard();

 private:
  struct Worker {
    RecordChunks<FaceIntersection> records;
    StageCounts counts;
  };
  const std::vector<BodyFrames>* bodies_ = nullptr;
  const PairKeys* keys_ = nullptr;
  tbb::enumerable_thread_specific<Worker> workers_;
};

}  // namespace clothcd::detail
