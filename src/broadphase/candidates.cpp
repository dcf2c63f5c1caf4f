// Canonical order of candidate pairs, so that results do not depend on the hierarchy or the thread schedule.
#include "broadphase/candidates.hpp"

#include <algorithm>

namespace clothcd::broadphase {

void sort_candidates(CandidateSet& candidates) {
  std::sort(candidates.vertex_face.begin(), candidates.vertex_face.end());
  std::sort(candidates.edge_edge.begin(), candidates.edge_edge.end());
  std::sort(candidates.face_face.begin(), candidates.face_face.end());
}

}  // namespace clothcd::broadphase
