// The distance stages of one state (see proximity_stage.hpp).
#include "proximity_stage.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "geometry/pair_distance.hpp"
#include "parallel_loop.hpp"

namespace clothcd::detail {

namespace {

// The four points of pair i of `block` at the start of its step (the state), in CcdQuery order.
std::array<Eigen::Vector3d, 4> state_points(const ccd::PairBlock& block, int i) {
  const ccd::PairLanes& group = block.group(i / ccd::PairLanes::kLanes);
  const int lane = i % ccd::PairLanes::kLanes;
  std::array<Eigen::Vector3d, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = Eigen::Vector3d(group.x[0][k][0][lane], group.x[0][k][1][lane], group.x[0][k][2][lane]);
  return x;
}

// The record of pair i of `block`, whose distance is `d`.
void fill_proximity(const ccd::PairBlock& block, int i, const geometry::PairDistance& d, Proximity& p) {
  p.kind = block.kind();
  p.vertices = block.vertices(i);
  p.distance = d.distance;
  p.parameters = d.parameters;
  p.direction = d.direction;
  p.type = d.type;
}

// True when `a` comes before `b`: smaller distance, then kind (vertex-face first), then key.
bool closer(const KeyedProximity& a, const KeyedProximity& b) {
  if (a.record.distance != b.record.distance) return a.record.distance < b.record.distance;
  if (a.record.kind != b.record.kind) return a.record.kind == PairKind::VertexFace;
  return a.key < b.key;
}

}  // namespace

void ProximityStage::begin(double distance, std::uint64_t edge_edge_offset) {
  distance_ = distance;
  edge_edge_offset_ = edge_edge_offset;
  discard();
}

void ProximityStage::discard() {
  for (Worker& w : workers_) {
    w.records.clear();
    w.counts = StageCounts{};
  }
}

long ProximityStage::run(ccd::PairBlock& block, const std::uint64_t* keys) {
  Worker& w = workers_.local();
  const auto t = StageClock::now();
  const bool vertex_face = block.kind() == PairKind::VertexFace;
  const std::uint64_t kind_offset = vertex_face ? 0 : edge_edge_offset_;
  long found = 0;
  geometry::PairDistance d;
  for (int i = 0; i < block.size(); ++i) {
    const std::array<Eigen::Vector3d, 4> x = state_points(block, i);
    const bool within = vertex_face ? geometry::point_triangle_within(x[0], x[1], x[2], x[3], distance_, d)
                                    : geometry::segment_segment_within(x[0], x[1], x[2], x[3], distance_, d);
    if (!within) continue;
    KeyedProximity& r = w.records.add();
    r.key = kind_offset + keys[block.tag(i)];
    fill_proximity(block, i, d, r.record);
    ++found;
  }
  w.counts.culled += block.size() - found;
  w.counts.exact_ms += milliseconds_since(t);
  return found;
}

void ProximityStage::take_counts(StageCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = StageCounts{};
  }
}

std::size_t ProximityStage::record_count() const {
  std::size_t count = 0;
  for (const Worker& w : workers_) count += w.records.size();
  return count;
}

MinimumDistanceStage::Worker::Worker() { closest.record.distance = std::numeric_limits<double>::infinity(); }

void MinimumDistanceStage::begin(double upper_bound, std::uint64_t edge_edge_offset) {
  upper_bound_ = upper_bound;
  edge_edge_offset_ = edge_edge_offset;
  discard();
  search_bound_.store(std::numeric_limits<double>::infinity(), std::memory_order_relaxed);
  if (std::isfinite(upper_bound)) lower_bound_to(upper_bound);
}

void MinimumDistanceStage::discard() {
  for (Worker& w : workers_) {
    w.closest = KeyedProximity{};
    w.closest.record.distance = std::numeric_limits<double>::infinity();
    w.counts = StageCounts{};
  }
}

void MinimumDistanceStage::lower_bound_to(double distance) {
  // A pair's box gap is at most its exact distance, which is at most its reported one times 1 + 2^-40: a bound of
  // (1 + 2^-39) times the reported minimum, rounded up, keeps every pair that could be reported at or below it.
  const double bound = std::nextafter(distance * (1.0 + 2.0 * kDistanceRelativeError),
                                      std::numeric_limits<double>::infinity());
  double current = search_bound_.load(std::memory_order_relaxed);
  while (bound < current && !search_bound_.compare_exchange_weak(current, bound, std::memory_order_relaxed)) {
  }
}

long MinimumDistanceStage::run(ccd::PairBlock& block, const std::uint64_t* keys) {
  Worker& w = workers_.local();
  const auto t = StageClock::now();
  const bool vertex_face = block.kind() == PairKind::VertexFace;
  const std::uint64_t kind_offset = vertex_face ? 0 : edge_edge_offset_;
  geometry::PairDistance d;
  for (int i = 0; i < block.size(); ++i) {
    const std::array<Eigen::Vector3d, 4> x = state_points(block, i);
    // A pair at or beyond the search's bound can neither beat nor tie the closest so far (see lower_bound_to), so
    // the exact membership test, cheap for most pairs, spares measuring them.
    const double bound = search_bound_.load(std::memory_order_relaxed);
    const bool within = vertex_face ? geometry::point_triangle_within(x[0], x[1], x[2], x[3], bound, d)
                                    : geometry::segment_segment_within(x[0], x[1], x[2], x[3], bound, d);
    if (!within) continue;
    KeyedProximity candidate;
    candidate.key = kind_offset + keys[block.tag(i)];
    fill_proximity(block, i, d, candidate.record);
    if (!closer(candidate, w.closest)) continue;
    w.closest = candidate;
    lower_bound_to(d.distance);
  }
  w.counts.exact_ms += milliseconds_since(t);
  return 0;
}

KeyedProximity MinimumDistanceStage::closest() const {
  // A pair must be closer than the upper bound: one at it is not closer than this one (see closer()).
  KeyedProximity best;
  best.record.distance = upper_bound_;
  for (const Worker& w : workers_) {
    if (closer(w.closest, best)) best = w.closest;
  }
  return best;
}

void MinimumDistanceStage::take_counts(StageCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = StageCounts{};
  }
}

}  // namespace clothcd::detail
