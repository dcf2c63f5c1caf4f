// The questions of one state (see collision_detector.hpp): the hierarchies of the state refitted to its positions
// (boxes inflated by the distance asked, or not at all for the minimum), then the candidate search into the pair
// stream and the stage of the question.
#include <cmath>
#include <stdexcept>
#include <string>

#include "clothcd/detection/collision_detector.hpp"
#include "detector_impl.hpp"
#include "parallel_loop.hpp"

namespace clothcd {

namespace {

using Clock = detail::StageClock;
using detail::milliseconds_since;

// The stats of a state query: `found`'s counts, the refit time already set, and the search's wall time split between
// the candidate search and the stage in proportion to the threads' time in each.
void fill_state_stats(const detail::StageCounts& found, double wall_ms, double task_ms, long records,
                      DetectionStats& stats) {
  const double scale = task_ms > 0 && task_ms >= found.exact_ms ? wall_ms / task_ms : 1.0;
  stats.candidates_vertex_face = found.vertex_face + found.face_face;
  stats.candidates_edge_edge = found.edge_edge;
  stats.culled = found.culled;
  stats.collisions = records;
  stats.exact_ms = scale * found.exact_ms;
  stats.traversal_ms = std::max(0.0, wall_ms - stats.exact_ms);
}

}  // namespace

const std::vector<Proximity>& CollisionDetector::proximity(const PositionsRef& positions, double distance) {
  Impl& d = *impl_;
  if (!(distance > 0.0) || !std::isfinite(distance)) {
    throw std::invalid_argument("proximity: the distance must be finite and > 0");
  }
  d.begin_state_call(positions, "proximity");
  d.proximities.clear();
  detail::StageCounts found;
  double wall_ms = 0, task_ms = 0;
  try {
    auto t = Clock::now();
    d.stats.rebuilds = d.bodies.refit_state(d.state_positions, distance);
    d.stats.refit_ms = milliseconds_since(t);
    t = Clock::now();
    d.frames = d.bodies.state_frames(d.state_positions);
    d.keys.assign(d.frames);
    d.proximity_stage.begin(distance, d.keys.vertex_face_key_count());
    d.search_state(d.proximity_stage, d.plan.traversal, d.budgeted(), found, task_ms);
    d.proximity_stage.take_counts(found);
    d.proximities.take(d.proximity_stage, d.plan.settings.max_collisions);
    d.proximities.sort(false);
    wall_ms = milliseconds_since(t);
  } catch (...) {
    d.proximities.clear();
    d.stream.discard();
    d.proximity_stage.discard();
    throw;
  }
  fill_state_stats(found, wall_ms, task_ms, static_cast<long>(d.proximities.size()), d.stats);
  return d.proximities.records();
}

MinimumDistance CollisionDetector::minimum_distance(const PositionsRef& positions, double upper_bound) {
  Impl& d = *impl_;
  if (!(upper_bound > 0.0)) throw std::invalid_argument("minimum_distance: the upper bound must be > 0");
  d.begin_state_call(positions, "minimum_distance");
  detail::StageCounts found;
  double wall_ms = 0, task_ms = 0;
  MinimumDistance answer;
  try {
    auto t = Clock::now();
    d.stats.rebuilds = d.bodies.refit_state(d.state_positions, 0.0);
    d.stats.refit_ms = milliseconds_since(t);
    t = Clock::now();
    d.frames = d.bodies.state_frames(d.state_positions);
    d.keys.assign(d.frames);
    d.minimum_stage.begin(upper_bound, d.keys.vertex_face_key_count());
    broadphase::TraversalSettings traversal = d.plan.traversal;
    traversal.gap_bound = &d.minimum_stage.search_bound();
    d.search_state(d.minimum_stage, traversal, d.budgeted(), found, task_ms);
    d.minimum_stage.take_counts(found);
    const detail::KeyedProximity closest = d.minimum_stage.closest();
    answer.found = closest.record.distance < upper_bound;
    answer.distance = closest.record.distance;
    if (answer.found) answer.pair = closest.record;
    wall_ms = milliseconds_since(t);
  } catch (...) {
    d.stream.discard();
    d.minimum_stage.discard();
    throw;
  }
  fill_state_stats(found, wall_ms, task_ms, answer.found ? 1 : 0, d.stats);
  return answer;
}

void CollisionDetector::Impl::search_intersections(const detail::StreamLimits& limits, detail::StageCounts& found,
                                                   double& wall_ms, double& task_ms) {
  auto t = Clock::now();
  stats.rebuilds = bodies.refit_state(state_positions, 0.0);
  stats.refit_ms = milliseconds_since(t);
  t = Clock::now();
  frames = bodies.state_frames(state_positions);
  keys.assign(frames);
  intersection_stage.begin(frames, keys);
  broadphase::TraversalSettings traversal = plan.traversal;
  traversal.pairs = broadphase::SearchedPairs::FaceFace;
  try {
    search_state(intersection_stage, traversal, limits, found, task_ms);
  } catch (const detail::SearchEnded&) {
    // is_intersection_free's first crossing: the answer is known.
  }
  intersection_stage.take_counts(found);
  wall_ms = milliseconds_since(t);
}

const std::vector<FaceIntersection>& CollisionDetector::intersections(const PositionsRef& positions) {
  Impl& d = *impl_;
  d.begin_state_call(positions, "intersections");
  d.intersecting.clear();
  detail::StageCounts found;
  double wall_ms = 0, task_ms = 0;
  try {
    d.search_intersections(d.budgeted(), found, wall_ms, task_ms);
    const auto t = Clock::now();
    d.intersecting.take(d.intersection_stage, d.plan.settings.max_collisions);
    d.intersecting.sort(false);
    wall_ms += milliseconds_since(t);
  } catch (...) {
    d.intersecting.clear();
    d.stream.discard();
    d.intersection_stage.discard();
    throw;
  }
  fill_state_stats(found, wall_ms, task_ms, static_cast<long>(d.intersecting.size()), d.stats);
  return d.intersecting.records();
}

bool CollisionDetector::is_intersection_free(const PositionsRef& positions) {
  Impl& d = *impl_;
  d.begin_state_call(positions, "is_intersection_free");
  detail::StageCounts found;
  double wall_ms = 0, task_ms = 0;
  detail::StreamLimits limits = d.budgeted();
  limits.stop_at = 1;
  std::size_t crossing = 0;
  try {
    d.search_intersections(limits, found, wall_ms, task_ms);
    crossing = d.intersection_stage.record_count();
  } catch (...) {
    d.stream.discard();
    d.intersection_stage.discard();
    throw;
  }
  d.intersection_stage.discard();
  fill_state_stats(found, wall_ms, task_ms, static_cast<long>(crossing), d.stats);
  return crossing == 0;
}

}  // namespace clothcd
