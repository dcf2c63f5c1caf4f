// Reuse of a detect() call's pair work by the next call of the same step (see pair_batch.hpp).
#include "pair_batch.hpp"

#include <cstring>

namespace clothcd::detail {

void PairBatch::resize_to_candidates() {
  refs.resize(size());
  keep.resize(size());
  results.resize(size());
}

std::size_t find_moved_rows(const Vertices& before, const Vertices& now, std::vector<std::uint8_t>& moved) {
  const std::size_t rows = static_cast<std::size_t>(now.rows());
  moved.assign(rows, 0);
  std::size_t count = 0;
  for (std::size_t v = 0; v < rows; ++v) {
    moved[v] = std::memcmp(before.data() + 3 * v, now.data() + 3 * v, 3 * sizeof(double)) != 0 ? 1 : 0;
    count += moved[v];
  }
  return count;
}

std::vector<std::size_t> merge_unmoved(const PairBatch& previous, const std::vector<std::uint8_t>& moved,
                                       const broadphase::CandidateSet& fresh, PairBatch& next) {
  auto unmoved = [&](std::size_t i) {
    for (const VertexRef& r : previous.refs[i]) {
      if (r.body == 0 && moved[r.vertex] != 0) return false;
    }
    return true;
  };
  const std::size_t previous_vf = previous.candidates.vertex_face.size();
  next.candidates.clear();
  std::vector<std::size_t> from;  // position in `previous` of each reused pair, in next's order
  from.reserve(previous.size());
  for (std::size_t i = 0; i < previous_vf; ++i) {
    if (!unmoved(i)) continue;
    from.push_back(i);
    next.candidates.vertex_face.push_back(previous.candidates.vertex_face[i]);
  }
  const std::size_t reused_vf = from.size();
  for (std::size_t i = previous_vf; i < previous.size(); ++i) {
    if (!unmoved(i)) continue;
    from.push_back(i);
    next.candidates.edge_edge.push_back(previous.candidates.edge_edge[i - previous_vf]);
  }
  const std::size_t reused_ee = from.size() - reused_vf;
  next.candidates.vertex_face.insert(next.candidates.vertex_face.end(), fresh.vertex_face.begin(),
                                     fresh.vertex_face.end());
  next.candidates.edge_edge.insert(next.candidates.edge_edge.end(), fresh.edge_edge.begin(), fresh.edge_edge.end());
  next.resize_to_candidates();

  const std::size_t next_vf = next.candidates.vertex_face.size();
  std::vector<std::size_t> todo;
  todo.reserve(fresh.size());
  auto copy = [&](std::size_t to, std::size_t i) {
    next.refs[to] = previous.refs[i];
    next.keep[to] = previous.keep[i];
    if (previous.keep[i]) next.results[to] = previous.results[i];  // culled pairs have no result
  };
  for (std::size_t j = 0; j < reused_vf; ++j) copy(j, from[j]);
  for (std::size_t p = reused_vf; p < next_vf; ++p) todo.push_back(p);
  for (std::size_t j = 0; j < reused_ee; ++j) copy(next_vf + j, from[reused_vf + j]);
  for (std::size_t p = next_vf + reused_ee; p < next.size(); ++p) todo.push_back(p);
  return todo;
}

}  // namespace clothcd::detail
