// The collecting sink (collecting_sink.hpp): a search's chunks appended to one set under a lock, and the searches run
// into it.
#include "broadphase/collecting_sink.hpp"

namespace clothcd::broadphase {

void CollectingSink::consume(const CandidateSet& chunk) {
  const std::lock_guard<std::mutex> lock(mutex_);
  out_.vertex_face.insert(out_.vertex_face.end(), chunk.vertex_face.begin(), chunk.vertex_face.end());
  out_.edge_edge.insert(out_.edge_edge.end(), chunk.edge_edge.begin(), chunk.edge_edge.end());
  out_.face_face.insert(out_.face_face.end(), chunk.face_face.begin(), chunk.face_face.end());
}

void find_self_candidates(const BodyView& body, const TraversalSettings& settings, CandidateSet& out,
                          TraversalStats* stats) {
  CollectingSink sink(out);
  find_self_candidates(body, settings, sink, stats);
}

void find_pair_candidates(const BodyView& a, const BodyView& b, const TraversalSettings& settings, CandidateSet& out,
                          TraversalStats* stats) {
  CollectingSink sink(out);
  find_pair_candidates(a, b, settings, sink, stats);
}

}  // namespace clothcd::broadphase
