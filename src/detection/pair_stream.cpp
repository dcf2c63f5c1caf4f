// The detector's pair stream (see pair_stream.hpp).
#include "pair_stream.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "clothcd/detection/detection_errors.hpp"

namespace clothcd::detail {

void PairKeys::assign(const std::vector<BodyFrames>& bodies) {
  const std::size_t n = bodies.size();
  vertex_base_.assign(n + 1, 0);
  face_base_.assign(n + 1, 0);
  edge_base_.assign(n + 1, 0);
  for (std::size_t b = 0; b < n; ++b) {
    const broadphase::BodyTopology& t = *bodies[b].topology;
    vertex_base_[b + 1] = vertex_base_[b] + static_cast<std::uint64_t>(t.vertex_count);
    face_base_[b + 1] = face_base_[b] + static_cast<std::uint64_t>(t.face_count());
    edge_base_[b + 1] = edge_base_[b] + static_cast<std::uint64_t>(t.edge_count());
  }
}

long PairStage::run(ccd::PairBlock&, const std::uint64_t*) {
  throw std::logic_error("pair stream: this stage takes face pairs, not pair blocks");
}

long PairStage::run_faces(const broadphase::FaceFaceCandidate*, std::size_t) {
  throw std::logic_error("pair stream: this stage takes pair blocks, not face pairs");
}

PairStream::PairStream(int block_pairs) : workers_([block_pairs] { return Worker(block_pairs); }) {
  Worker probe(block_pairs);  // a block that cannot be made is an error here, not in a search thread
}

void PairStream::begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys, const StreamLimits& limits,
                       PairStage& stage, long kept) {
  bodies_ = &bodies;
  keys_ = &keys;
  stage_ = &stage;
  limits_ = limits;
  discard();
  found_.store(kept, std::memory_order_relaxed);
}

void PairStream::discard() {
  for (Worker& w : workers_) {
    w.block.reset(PairKind::VertexFace);
    w.vertex_face = w.edge_edge = w.face_face = 0;
  }
}

void PairStream::take_candidate_counts(long& vertex_face, long& edge_edge, long& face_face) {
  for (Worker& w : workers_) {
    vertex_face += w.vertex_face;
    edge_edge += w.edge_edge;
    face_face += w.face_face;
    w.vertex_face = w.edge_edge = w.face_face = 0;
  }
}

void PairStream::check_stop() const {
  const std::function<bool()>* cancel = limits_.cancel;
  if (cancel != nullptr && *cancel && (*cancel)()) throw DetectionCancelled();
  const long found = found_.load(std::memory_order_relaxed);
  if (limits_.stop_at >= 0 && found >= limits_.stop_at) throw SearchEnded();
  if (limits_.max_records >= 0 && found > limits_.max_records) {
    throw CollisionBudgetExceeded(found, limits_.max_records);
  }
}

void PairStream::run_block(Worker& w) {
  if (w.block.size() == 0) return;
  check_stop();
  const long records = stage_->run(w.block, w.keys.data());
  if (records > 0) found_.fetch_add(records, std::memory_order_relaxed);
  w.block.reset(w.block.kind());
}

void PairStream::consume(const broadphase::CandidateSet& chunk) {
  Worker& w = workers_.local();
  const std::vector<BodyFrames>& bodies = *bodies_;
  const auto row = [&](const Vertices* positions, int vertex) { return positions->data() + 3 * vertex; };
  // Appends the pair of vertices `v` to the block, running the block first when it is full.
  const auto add = [&](const std::array<VertexRef, 4>& v, std::uint64_t key) {
    if (w.block.full()) run_block(w);
    std::array<const double*, 4> start, end;
    for (int k = 0; k < 4; ++k) {
      const BodyFrames& body = bodies[static_cast<std::size_t>(v[k].body)];
      start[k] = row(body.start, v[k].vertex);
      end[k] = row(body.end, v[k].vertex);
    }
    w.keys[static_cast<std::size_t>(w.block.size())] = key;
    w.block.push(v, static_cast<std::uint64_t>(w.block.size()), start, end);
  };
  w.block.reset(PairKind::VertexFace);
  for (const broadphase::VertexFaceCandidate& c : chunk.vertex_face) {
    const auto& faces = bodies[static_cast<std::size_t>(c.face_body)].topology->faces;
    add({VertexRef{c.vertex_body, c.vertex}, VertexRef{c.face_body, faces(c.face, 0)},
         VertexRef{c.face_body, faces(c.face, 1)}, VertexRef{c.face_body, faces(c.face, 2)}},
        keys_->vertex_face(c.vertex_body, c.vertex, c.face_body, c.face));
  }
  run_block(w);
  w.block.reset(PairKind::EdgeEdge);
  for (const broadphase::EdgeEdgeCandidate& c : chunk.edge_edge) {
    const std::vector<int>& ea = bodies[static_cast<std::size_t>(c.body_a)].topology->edges;
    const std::vector<int>& eb = bodies[static_cast<std::size_t>(c.body_b)].topology->edges;
    add({VertexRef{c.body_a, ea[2 * static_cast<std::size_t>(c.edge_a)]},
         VertexRef{c.body_a, ea[2 * static_cast<std::size_t>(c.edge_a) + 1]},
         VertexRef{c.body_b, eb[2 * static_cast<std::size_t>(c.edge_b)]},
         VertexRef{c.body_b, eb[2 * static_cast<std::size_t>(c.edge_b) + 1]}},
        keys_->edge_edge(c.body_a, c.edge_a, c.body_b, c.edge_b));
  }
  run_block(w);
  // Face pairs go to the stage as they are, a block's worth at a time.
  const std::size_t slice = static_cast<std::size_t>(w.block.capacity());
  for (std::size_t from = 0; from < chunk.face_face.size(); from += slice) {
    check_stop();
    const long records = stage_->run_faces(chunk.face_face.data() + from, std::min(slice, chunk.face_face.size() - from));
    if (records > 0) found_.fetch_add(records, std::memory_order_relaxed);
  }
  w.face_face += static_cast<long>(chunk.face_face.size());
  w.vertex_face += static_cast<long>(chunk.vertex_face.size());
  w.edge_edge += static_cast<long>(chunk.edge_edge.size());
}

}  // namespace clothcd::detail
