// The narrow phase as a candidate sink (see pair_pipeline.hpp).
#include "pair_pipeline.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "clothcd/detection/detection_errors.hpp"
#include "parallel_loop.hpp"

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

void PipelineCounts::add(const PipelineCounts& o) {
  vertex_face += o.vertex_face;
  edge_edge += o.edge_edge;
  culled += o.culled;
  culler.add(o.culler);
  culling_ms += o.culling_ms;
  exact_ms += o.exact_ms;
}

PairPipeline::PairPipeline(const PipelineSettings& settings, int block_pairs)
    : settings_(settings), workers_([block_pairs] { return Worker(block_pairs); }) {
  Worker probe(block_pairs);  // a block that cannot be made is an error here, not in a search thread
}

void PairPipeline::begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys,
                         const PipelineSearch& search, long kept) {
  bodies_ = &bodies;
  keys_ = &keys;
  search_ = search;
  discard();
  found_.store(kept, std::memory_order_relaxed);
  earliest_toi_.store(search.earliest_bound, std::memory_order_relaxed);
}

void PairPipeline::discard() {
  for (Worker& w : workers_) {
    w.block.reset(PairKind::VertexFace);
    std::vector<std::vector<KeyedCollision>>().swap(w.collisions);
    w.earliest = KeyedCollision{};
    w.earliest.collision.toi = std::numeric_limits<double>::infinity();
    w.counts = PipelineCounts{};
  }
}

void PairPipeline::check_stop() const {
  const std::function<bool()>* cancel = search_.cancel;
  if (cancel != nullptr && *cancel && (*cancel)()) throw DetectionCancelled();
  const long found = found_.load(std::memory_order_relaxed);
  if (search_.exact && found > settings_.max_collisions) {
    throw CollisionBudgetExceeded(found, settings_.max_collisions);
  }
}

namespace {

// The collision of survivor i of `block`, whose exact test gave `r`.
void fill_collision(const ccd::PairBlock& block, int i, const ccd::CcdResult& r, Collision& c) {
  c.kind = block.kind();
  c.vertices = block.vertices(i);
  c.toi = r.toi;
  c.parameters = r.parameters;
  c.normal = r.normal;
  c.conservative = r.state == ccd::CcdState::ConservativeHit;
}

}  // namespace

bool earlier_impact(const KeyedCollision& a, const KeyedCollision& b) {
  if (a.collision.toi != b.collision.toi) return a.collision.toi < b.collision.toi;
  if (a.collision.kind != b.collision.kind) return a.collision.kind == PairKind::VertexFace;
  return a.key < b.key;
}

KeyedCollision& PairPipeline::add_collision(Worker& w) {
  if (w.collisions.empty() || w.collisions.back().size() == kChunkCollisions) {
    w.collisions.emplace_back().reserve(kChunkCollisions);
  }
  return w.collisions.back().emplace_back();
}

void PairPipeline::consume(const broadphase::CandidateSet& chunk) {
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
  w.counts.vertex_face += static_cast<long>(chunk.vertex_face.size());
  w.counts.edge_edge += static_cast<long>(chunk.edge_edge.size());
}

void PairPipeline::run_block(Worker& w) const {
  ccd::PairBlock& block = w.block;
  const int n = block.size();
  if (n == 0) return;
  check_stop();
  const PipelineSettings& s = settings_;
  const PipelineSearch& search = search_;
  if (search.observer != nullptr) {
    if (!w.observed) w.observed = std::make_unique<ccd::PairBlock>(block.capacity());
    *w.observed = block;
    w.observed_culled.assign(static_cast<std::size_t>(n), 1);
    w.observed_colliding.assign(static_cast<std::size_t>(n), 0);
  }
  auto t = StageClock::now();
  // Survivors [0, filtered) passed the filters `applied`; the culler's Keep pairs behind them met no filter.
  int filtered = 0, survivors = 0;
  ccd::CcdFilter applied = s.filter;
  if (s.culler != nullptr) {
    const CullerSurvivors left = cull_with_culler(*s.culler, block, s.ccd, s.projection, w.culler, w.counts.culler);
    filtered = left.filtered;
    survivors = left.filtered + left.kept;
    applied = ccd::CcdFilter::Combined;
  } else {
    filtered = survivors = ccd::cull_pair_block(block, n, s.filter, s.ccd, s.projection, w.culled);
  }
  w.counts.culled += n - survivors;
  w.counts.culling_ms += milliseconds_since(t);
  if (search.exact && search.earliest) {
    find_earliest(w, survivors, filtered, applied);
  } else if (search.exact) {
    t = StageClock::now();
    long hits = 0;
    for (int i = 0; i < survivors; ++i) {
      // The filters' tests are not repeated on the pairs that passed them.
      const ccd::CcdResult r =
          ccd::continuous_collision_after_filter(block.query(i), s.ccd, i < filtered ? applied : ccd::CcdFilter::None);
      if (!r.hit) continue;
      if (search.observer != nullptr) w.observed_colliding[block.tag(i)] = 1;
      KeyedCollision& h = add_collision(w);
      ++hits;
      h.key = w.keys[block.tag(i)];
      fill_collision(block, i, r, h.collision);
    }
    w.counts.exact_ms += milliseconds_since(t);
    if (hits > 0) found_.fetch_add(hits, std::memory_order_relaxed);
  }
  if (search.observer != nullptr) show_block(w, survivors);
  block.reset(block.kind());
}

void PairPipeline::find_earliest(Worker& w, int survivors, int filtered, ccd::CcdFilter applied) const {
  const PipelineSettings& s = settings_;
  const ccd::PairBlock& block = w.block;
  const auto t = StageClock::now();
  const std::uint64_t kind_offset = block.kind() == PairKind::EdgeEdge ? keys_->vertex_face_key_count() : 0;
  long hits = 0;
  for (int i = 0; i < survivors; ++i) {
    const double until = std::min(search_.window, earliest_toi_.load(std::memory_order_relaxed));
    const ccd::CcdResult r = ccd::continuous_collision_until(block.query(i), s.ccd,
                                                             i < filtered ? applied : ccd::CcdFilter::None, until);
    hits += r.hit ? 1 : 0;
    double best = earliest_toi_.load(std::memory_order_relaxed);
    if (!r.hit || r.toi > best) continue;
    KeyedCollision hit;
    hit.key = kind_offset + w.keys[block.tag(i)];
    fill_collision(block, i, r, hit.collision);
    if (earlier_impact(hit, w.earliest)) w.earliest = hit;
    while (r.toi < best && !earliest_toi_.compare_exchange_weak(best, r.toi, std::memory_order_relaxed)) {
    }
  }
  w.counts.exact_ms += milliseconds_since(t);
  if (hits > 0) found_.fetch_add(hits, std::memory_order_relaxed);
}

KeyedCollision PairPipeline::earliest() const {
  KeyedCollision best;
  best.collision.toi = std::numeric_limits<double>::infinity();
  for (const Worker& w : workers_) {
    if (earlier_impact(w.earliest, best)) best = w.earliest;
  }
  return best;
}

void PairPipeline::show_block(Worker& w, int survivors) const {
  for (int i = 0; i < survivors; ++i) w.observed_culled[w.block.tag(i)] = 0;
  ObservedBlock seen;
  seen.pairs = w.observed.get();
  seen.keys = w.keys.data();
  seen.culled = w.observed_culled.data();
  seen.colliding = w.observed_colliding.data();
  (*search_.observer)(seen);
}

void PairPipeline::add_counts(PipelineCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = PipelineCounts{};
  }
}

std::size_t PairPipeline::collision_count() const {
  std::size_t count = 0;
  for (const Worker& w : workers_) {
    for (const std::vector<KeyedCollision>& chunk : w.collisions) count += chunk.size();
  }
  return count;
}

}  // namespace clothcd::detail
