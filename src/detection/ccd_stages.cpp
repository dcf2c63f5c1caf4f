// The stages of the questions of a step (see ccd_stages.hpp).
#include "ccd_stages.hpp"

#include <algorithm>

#include "parallel_loop.hpp"

namespace clothcd::detail {

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

// The filters survivor i has passed already (the exact test does not repeat them).
ccd::CcdFilter filters_passed(const BlockSurvivors& left, int i) {
  return i < left.filtered ? left.applied : ccd::CcdFilter::None;
}

}  // namespace

bool earlier_impact(const KeyedCollision& a, const KeyedCollision& b) {
  if (a.record.toi != b.record.toi) return a.record.toi < b.record.toi;
  if (a.record.kind != b.record.kind) return a.record.kind == PairKind::VertexFace;
  return a.key < b.key;
}

StepCollisionStage::StepCollisionStage(const PairTestSettings& settings) : settings_(settings) {}

void StepCollisionStage::begin(bool test, const BlockObserver* observer, std::uint64_t edge_edge_offset) {
  test_ = test;
  observer_ = observer;
  edge_edge_offset_ = edge_edge_offset;
  discard();
}

void StepCollisionStage::discard() {
  for (Worker& w : workers_) {
    w.collisions.clear();
    w.counts = StageCounts{};
  }
}

long StepCollisionStage::run(ccd::PairBlock& block, const std::uint64_t* keys) {
  Worker& w = workers_.local();
  const int n = block.size();
  if (observer_ != nullptr) {
    if (!w.observed) w.observed = std::make_unique<ccd::PairBlock>(block.capacity());
    *w.observed = block;
    w.observed_culled.assign(static_cast<std::size_t>(n), 1);
    w.observed_colliding.assign(static_cast<std::size_t>(n), 0);
  }
  const BlockSurvivors left = cull_block(block, settings_, w.scratch, w.counts);
  long hits = 0;
  if (test_) {
    const auto t = StageClock::now();
    const std::uint64_t kind_offset = block.kind() == PairKind::EdgeEdge ? edge_edge_offset_ : 0;
    for (int i = 0; i < left.survivors; ++i) {
      const ccd::CcdResult r =
          ccd::continuous_collision_after_filter(block.query(i), settings_.ccd, filters_passed(left, i));
      if (!r.hit) continue;
      if (observer_ != nullptr) w.observed_colliding[block.tag(i)] = 1;
      KeyedCollision& h = w.collisions.add();
      ++hits;
      h.key = kind_offset + keys[block.tag(i)];
      fill_collision(block, i, r, h.record);
    }
    w.counts.exact_ms += milliseconds_since(t);
  }
  if (observer_ != nullptr) show_block(w, block, keys, left.survivors);
  return hits;
}

void StepCollisionStage::show_block(Worker& w, const ccd::PairBlock& block, const std::uint64_t* keys,
                                    int survivors) const {
  for (int i = 0; i < survivors; ++i) w.observed_culled[block.tag(i)] = 0;
  ObservedBlock seen;
  seen.pairs = w.observed.get();
  seen.keys = keys;
  seen.culled = w.observed_culled.data();
  seen.colliding = w.observed_colliding.data();
  (*observer_)(seen);
}

void StepCollisionStage::take_counts(StageCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = StageCounts{};
  }
}

std::size_t StepCollisionStage::record_count() const {
  std::size_t count = 0;
  for (const Worker& w : workers_) count += w.collisions.size();
  return count;
}

EarliestImpactStage::EarliestImpactStage(const PairTestSettings& settings) : settings_(settings) {}

void EarliestImpactStage::begin(double window, double earliest_bound, std::uint64_t edge_edge_offset) {
  window_ = window;
  edge_edge_offset_ = edge_edge_offset;
  discard();
  earliest_toi_.store(earliest_bound, std::memory_order_relaxed);
}

void EarliestImpactStage::discard() {
  for (Worker& w : workers_) {
    w.earliest = KeyedCollision{};
    w.earliest.record.toi = std::numeric_limits<double>::infinity();
    w.counts = StageCounts{};
  }
}

long EarliestImpactStage::run(ccd::PairBlock& block, const std::uint64_t* keys) {
  Worker& w = workers_.local();
  const BlockSurvivors left = cull_block(block, settings_, w.scratch, w.counts);
  const auto t = StageClock::now();
  const std::uint64_t kind_offset = block.kind() == PairKind::EdgeEdge ? edge_edge_offset_ : 0;
  long hits = 0;
  for (int i = 0; i < left.survivors; ++i) {
    const double until = std::min(window_, earliest_toi_.load(std::memory_order_relaxed));
    const ccd::CcdResult r =
        ccd::continuous_collision_until(block.query(i), settings_.ccd, filters_passed(left, i), until);
    hits += r.hit ? 1 : 0;
    double best = earliest_toi_.load(std::memory_order_relaxed);
    if (!r.hit || r.toi > best) continue;
    KeyedCollision hit;
    hit.key = kind_offset + keys[block.tag(i)];
    fill_collision(block, i, r, hit.record);
    if (earlier_impact(hit, w.earliest)) w.earliest = hit;
    while (r.toi < best && !earliest_toi_.compare_exchange_weak(best, r.toi, std::memory_order_relaxed)) {
    }
  }
  w.counts.exact_ms += milliseconds_since(t);
  return hits;
}

KeyedCollision EarliestImpactStage::earliest() const {
  KeyedCollision best;
  best.record.toi = std::numeric_limits<double>::infinity();
  for (const Worker& w : workers_) {
    if (earlier_impact(w.earliest, best)) best = w.earliest;
  }
  return best;
}

void EarliestImpactStage::take_counts(StageCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = StageCounts{};
  }
}

}  // namespace clothcd::detail
