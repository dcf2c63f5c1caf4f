// The detector of a simulation step (Jin et al., section 3): swept boxes and hierarchy refit (section 3.2), candidate
// search of cloth vs obstacles and cloth vs itself, culling by the algebraic non-penetration and spatial projection
// filters (sections 2.2, 2.3) or by a culler such as the pair network behind the filters (section 3.3), then the
// exact-safe continuous collision test of every surviving pair. The candidates are not stored: the pair stream
// (pair_stream.hpp) hands each search thread's candidates, block by block as they are found, to the stage of the
// question asked (ccd_stages.hpp), and only its records are kept, within the collision budget. In parts: the bodies
// and their hierarchies (detector_bodies.hpp), the collisions and their order (sorted_records.hpp: 96 + 16 bytes per
// collision at the peak) and the re-test of a repeated step (retest_cache.hpp); this file runs a call through them.
// The earliest-impact search runs the same search over consecutive time windows of the step (window_schedule.hpp),
// its stage testing each pair only up to the earliest contact found so far.
#include "clothcd/detection/collision_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "clothcd/ccd/ccd.hpp"
#include "detector_impl.hpp"
#include "parallel_loop.hpp"
#include "window_schedule.hpp"

namespace clothcd {
namespace {

using Clock = detail::StageClock;
using detail::milliseconds_since;

}  // namespace

CollisionDetector::CollisionDetector(const Faces& cloth_faces, int cloth_vertex_count, const DetectorSettings& settings)
    : impl_(std::make_unique<Impl>(cloth_faces, cloth_vertex_count, settings)) {}

CollisionDetector::~CollisionDetector() = default;
CollisionDetector::CollisionDetector(CollisionDetector&&) noexcept = default;
CollisionDetector& CollisionDetector::operator=(CollisionDetector&&) noexcept = default;

int CollisionDetector::add_obstacle(const TriangleMesh& mesh) { return impl_->bodies.add_obstacle(mesh); }

void CollisionDetector::set_obstacle_positions(int body, const PositionsRef& start, const PositionsRef& end) {
  detail::Body& o = impl_->bodies.obstacle(body, "set_obstacle_positions");
  detail::check_positions(start, o.rest.rows(), "set_obstacle_positions: start");
  detail::check_positions(end, o.rest.rows(), "set_obstacle_positions: end");
  o.start = start;
  o.end = end;
  o.stale = true;
  o.moving = true;
}

void CollisionDetector::set_obstacle_transforms(int body, const Eigen::Isometry3d& start, const Eigen::Isometry3d& end) {
  detail::Body& o = impl_->bodies.obstacle(body, "set_obstacle_transforms");
  if (!start.matrix().allFinite() || !end.matrix().allFinite()) {
    throw std::invalid_argument("set_obstacle_transforms: a transform has a NaN or infinite entry");
  }
  o.start = (o.rest * start.linear().transpose()).rowwise() + start.translation().transpose();
  o.end = (o.rest * end.linear().transpose()).rowwise() + end.translation().transpose();
  o.stale = true;
  o.moving = true;
}

int CollisionDetector::obstacle_count() const { return impl_->bodies.obstacle_count(); }

const std::vector<int>& CollisionDetector::edges(int body) const {
  if (body == 0) return impl_->bodies.cloth().topology.edges;
  return impl_->bodies.obstacle(body, "edges").topology.edges;
}

const std::vector<Collision>& CollisionDetector::detect(const PositionsRef& caller_start,
                                                       const PositionsRef& caller_end) {
  Impl& d = *impl_;
  d.begin_call(caller_start, caller_end, "detect");
  const Vertices& start = d.current_start;
  const Vertices& end = d.current_end;
  const bool reuse = d.may_reuse() && !d.bodies.any_obstacle_stale() && d.retest.repeats_last_step(start, end);
  d.retest.forget();  // until this call completes

  // The broad phase, the culling and the exact test run together (each thread's pairs go through them block by
  // block), so their times are the wall time of the search split in proportion to the threads' time in each.
  double wall_ms = 0, task_ms = 0, collect_ms = 0;
  detail::StageCounts replaced, found;
  try {
    if (reuse) {
      // The last call's pairs with a moved vertex, found again on the hierarchy and positions of that call: only
      // their count is needed, to keep the candidate and culled counts those of a full search.
      auto t = Clock::now();
      d.prepare(d.retest.start(), d.retest.end());
      d.step_stage.begin(false, nullptr, d.keys.vertex_face_key_count());
      d.search(d.step_stage, detail::StreamLimits{&d.cancel, -1}, 0, true, replaced, task_ms);
      d.step_stage.take_counts(replaced);
      wall_ms += milliseconds_since(t);
      d.collected.drop_moved(d.retest.moved());
    } else {
      d.collected.clear();
      d.counts = detail::StageCounts{};
    }

    auto t = Clock::now();
    d.stats.rebuilds = d.bodies.refit(start, end, d.plan.settings.thickness, reuse ? &d.retest.moved() : nullptr);
    d.stats.refit_ms = milliseconds_since(t);

    t = Clock::now();
    d.prepare(start, end);
    d.step_stage.begin(true, d.observer ? &d.observer : nullptr, d.keys.vertex_face_key_count());
    d.search(d.step_stage, d.budgeted(), static_cast<long>(d.collected.size()), reuse, found, task_ms);
    d.step_stage.take_counts(found);
    d.collected.take(d.step_stage, d.plan.settings.max_collisions);
    wall_ms += milliseconds_since(t);

    t = Clock::now();
    d.collected.sort(d.may_reuse());
    collect_ms = milliseconds_since(t);
  } catch (...) {
    d.discard();
    throw;
  }

  const double threads_ms = replaced.culling_ms + replaced.exact_ms + found.culling_ms + found.exact_ms;
  const double scale = task_ms > 0 && task_ms >= threads_ms ? wall_ms / task_ms : 1.0;
  d.stats.culling_ms = scale * (replaced.culling_ms + found.culling_ms);
  d.stats.exact_ms = scale * found.exact_ms + collect_ms;
  d.stats.traversal_ms = std::max(0.0, wall_ms - scale * threads_ms);
  d.stats.network_ms = scale * found.culler.culler_ms;
  d.stats.network_filters_ms = scale * found.culler.filters_ms;
  d.stats.network_dropped = found.culler.dropped;
  d.stats.network_overruled = found.culler.overruled;
  d.stats.network_kept = found.culler.kept;

  // A re-test's counts: the last call's, with the replaced pairs' taken out and the new ones' put in.
  const long previous = d.counts.vertex_face + d.counts.edge_edge;
  d.counts.vertex_face += found.vertex_face - replaced.vertex_face;
  d.counts.edge_edge += found.edge_edge - replaced.edge_edge;
  d.counts.culled += found.culled - replaced.culled;
  d.stats.candidates_vertex_face = d.counts.vertex_face;
  d.stats.candidates_edge_edge = d.counts.edge_edge;
  d.stats.culled = d.counts.culled;
  d.stats.collisions = static_cast<long>(d.collected.size());
  d.stats.reused = reuse ? previous - (replaced.vertex_face + replaced.edge_edge) : 0;

  if (d.may_reuse()) d.retest.remember(d.current_start, d.current_end);
  d.bodies.finish_step();
  return d.collected.records();
}

EarliestImpact CollisionDetector::earliest_impact(const PositionsRef& caller_start, const PositionsRef& caller_end) {
  Impl& d = *impl_;
  d.begin_call(caller_start, caller_end, "earliest_impact");
  d.retest.forget();  // the hierarchies hold a window's boxes, not those of the last detect()

  // The windows are consecutive parts of the step: a pair that comes into contact within one is among its
  // candidates, so once a window's search finds no contact, none comes before its end, and once it finds one, no pair
  // of a later window can come sooner. Each window's pairs are tested from the start of the step (before the window
  // they are clear) to its end or the earliest toi found so far.
  EarliestImpact answer;
  detail::KeyedCollision earliest;
  earliest.record.toi = std::numeric_limits<double>::infinity();
  double task_ms = 0, wall_ms = 0;
  detail::StageCounts found;
  const broadphase::BodyTopology& cloth = d.bodies.cloth().topology;
  // What a window costs whatever its length, counted as candidates: a box per vertex, a refit of every face and edge.
  const double fixed_cost = cloth.vertex_count + cloth.face_count() + cloth.edge_count();
  try {
    detail::WindowSchedule window(detail::relative_motion(cloth, d.current_start, d.current_end), fixed_cost);
    while (true) {
      ++answer.windows;
      const long candidates_before = found.vertex_face + found.edge_edge;
      auto t = Clock::now();
      d.stats.rebuilds += d.bodies.refit_part(d.current_start, d.current_end, window.from(), window.to(),
                                              d.plan.settings.thickness);
      d.stats.refit_ms += milliseconds_since(t);
      t = Clock::now();
      d.prepare(d.current_start, d.current_end);
      d.earliest_stage.begin(window.to(), earliest.record.toi, d.keys.vertex_face_key_count());
      d.search(d.earliest_stage, d.budgeted(), 0, false, found, task_ms);
      d.earliest_stage.take_counts(found);
      wall_ms += milliseconds_since(t);
      const detail::KeyedCollision in_window = d.earliest_stage.earliest();
      if (detail::earlier_impact(in_window, earliest)) earliest = in_window;
      if (earliest.record.toi <= window.to() || window.last()) break;
      window.advance(static_cast<double>(found.vertex_face + found.edge_edge - candidates_before));
    }
  } catch (...) {
    d.discard();
    d.bodies.finish_step();
    throw;
  }
  d.bodies.finish_step();

  const double scale = task_ms > 0 && task_ms >= found.culling_ms + found.exact_ms ? wall_ms / task_ms : 1.0;
  d.stats.culling_ms = scale * found.culling_ms;
  d.stats.exact_ms = scale * found.exact_ms;
  d.stats.traversal_ms = std::max(0.0, wall_ms - scale * (found.culling_ms + found.exact_ms));
  d.stats.candidates_vertex_face = found.vertex_face;
  d.stats.candidates_edge_edge = found.edge_edge;
  d.stats.culled = found.culled;
  answer.hit = std::isfinite(earliest.record.toi);
  d.stats.collisions = answer.hit ? 1 : 0;
  if (answer.hit) {
    answer.toi = earliest.record.toi;
    answer.pair = earliest.record;
  }
  return answer;
}

const DetectionStats& CollisionDetector::stats() const { return impl_->stats; }

void CollisionDetector::set_block_observer(BlockObserver observer) { impl_->observer = std::move(observer); }

void CollisionDetector::set_cancel_check(std::function<bool()> cancel) { impl_->cancel = std::move(cancel); }

}  // namespace clothcd
