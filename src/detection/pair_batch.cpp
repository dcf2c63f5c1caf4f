// Reuse of a detect() call's pair work by the next call of the same step (see pair_batch.hpp).
#include "pair_batch.hpp"

#include <algorithm>
#include <cstring>

namespace clothcd::detail {
namespace {

// Resizes the per-pair arrays (all but the queries) to the pairs.
void resize_to_pairs(PairBatch& batch) {
  batch.refs.resize(batch.size());
  batch.keep.resize(batch.size());
  batch.results.resize(batch.size());
}

// Moves the pair at position `from` (and its work) to position `to`.
void move_pair(PairBatch& batch, std::size_t from, std::size_t to) {
  batch.pairs[to] = batch.pairs[from];
  batch.refs[to] = batch.refs[from];
  batch.keep[to] = batch.keep[from];
  if (batch.keep[from]) batch.results[to] = batch.results[from];  // culled pairs have no result
}

// Writes the k-th pair of `fresh` (its vertex-face pairs first) into `out`.
void write_fresh(const broadphase::CandidateSet& fresh, std::size_t k, BatchPair& out) {
  const std::size_t vertex_face = fresh.vertex_face.size();
  if (k < vertex_face) {
    const broadphase::VertexFaceCandidate& c = fresh.vertex_face[k];
    out.kind = PairKind::VertexFace;
    out.fields = {c.vertex_body, c.vertex, c.face_body, c.face};
  } else {
    const broadphase::EdgeEdgeCandidate& c = fresh.edge_edge[k - vertex_face];
    out.kind = PairKind::EdgeEdge;
    out.fields = {c.body_a, c.edge_a, c.body_b, c.edge_b};
  }
}

// `positions` with the vertex-face pairs first, each kind in increasing order.
void order_by_kind(const PairBatch& batch, std::vector<std::size_t>& positions) {
  std::sort(positions.begin(), positions.end());
  std::stable_partition(positions.begin(), positions.end(),
                        [&](std::size_t i) { return batch.pairs[i].kind == PairKind::VertexFace; });
}

}  // namespace

void PairBatch::assign(const broadphase::CandidateSet& fresh, std::vector<std::size_t>& all) {
  // Written in place (building each pair as a temporary and appending it was a tenth of the candidate search's time).
  pairs.resize(fresh.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) write_fresh(fresh, k, pairs[k]);
  resize_to_pairs(*this);
  all.resize(size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
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

std::vector<std::size_t> replace_moved(PairBatch& batch, const std::vector<std::uint8_t>& moved,
                                       const broadphase::CandidateSet& fresh) {
  // A pair's cloth vertices index `moved`; obstacle vertices read a flag that is always 0 (one past the cloth's).
  std::vector<std::uint8_t> flags(moved.size() + 1, 0);
  std::copy(moved.begin(), moved.end(), flags.begin());
  const std::size_t never = moved.size();
  std::vector<std::size_t> holes;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    std::uint8_t any = 0;
    for (const VertexRef& r : batch.refs[i]) any |= flags[r.body == 0 ? static_cast<std::size_t>(r.vertex) : never];
    if (any) holes.push_back(i);
  }

  std::vector<std::size_t> todo;
  todo.reserve(fresh.size());
  const std::size_t placed_in_holes = std::min(holes.size(), fresh.size());
  for (std::size_t j = 0; j < placed_in_holes; ++j) {
    write_fresh(fresh, j, batch.pairs[holes[j]]);
    todo.push_back(holes[j]);
  }
  if (fresh.size() > holes.size()) {
    const std::size_t first_new = batch.size();
    batch.pairs.resize(first_new + fresh.size() - placed_in_holes);
    for (std::size_t i = first_new; i < batch.size(); ++i) {
      write_fresh(fresh, placed_in_holes + (i - first_new), batch.pairs[i]);
      todo.push_back(i);
    }
    resize_to_pairs(batch);
  } else {
    // The holes left over are the largest ones (the fresh pairs took the smallest): fill each from the end, largest
    // first. Every position after the smallest of them is such a hole or a pair that keeps its work, never a fresh one.
    for (std::size_t j = holes.size(); j-- > placed_in_holes;) {
      const std::size_t last = batch.size() - 1;
      if (holes[j] != last) move_pair(batch, last, holes[j]);
      batch.pairs.pop_back();
    }
    resize_to_pairs(batch);
  }
  order_by_kind(batch, todo);
  return todo;
}

}  // namespace clothcd::detail
