#pragma once
// The collision detector's state (internal): its plan, bodies, pair stream and stages, the records of the last calls
// and the re-test cache, shared by the calls of a step (collision_detector.cpp) and of one state (state_queries.cpp).
#include <functional>
#include <string>
#include <vector>

#include "broadphase/traversal.hpp"
#include "ccd_stages.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/detection/face_intersection.hpp"
#include "clothcd/detection/proximity.hpp"
#include "detector_bodies.hpp"
#include "detector_plan.hpp"
#include "intersection_stage.hpp"
#include "pair_stream.hpp"
#include "proximity_stage.hpp"
#include "retest_cache.hpp"
#include "sorted_records.hpp"

namespace clothcd {

namespace detail {

/// Checks that `positions` has `rows` rows and finite coordinates (std::invalid_argument naming `what` otherwise).
inline void check_positions(const PositionsRef& positions, Eigen::Index rows, const std::string& what) {
  if (positions.rows() != rows) {
    throw std::invalid_argument(what + " has " + std::to_string(positions.rows()) + " rows, expected " +
                                std::to_string(rows));
  }
  if (!positions.allFinite()) throw std::invalid_argument(what + " has a NaN or infinite coordinate");
}

}  // namespace detail

/// The detector's state behind its public interface.
struct CollisionDetector::Impl {
  Impl(const Faces& cloth_faces, int cloth_vertex_count, const DetectorSettings& settings)
      : plan(settings),
        bodies(cloth_faces, cloth_vertex_count, plan.cloth_hierarchy, plan.obstacle_volume),
        stream(plan.settings.block_pairs),
        step_stage(plan.pair_tests),
        earliest_stage(plan.pair_tests) {}

  detail::DetectorPlan plan;  // the settings, checked and translated once
  BlockObserver observer;     // set_block_observer
  std::function<bool()> cancel;  // set_cancel_check
  detail::DetectorBodies bodies;
  detail::PairStream stream;  // the candidates in blocks, to the search's stage as they are found
  detail::StepCollisionStage step_stage;
  detail::EarliestImpactStage earliest_stage;
  detail::ProximityStage proximity_stage;
  detail::MinimumDistanceStage minimum_stage;
  detail::IntersectionStage intersection_stage;
  std::vector<detail::BodyFrames> frames;  // what the stream reads, per body id
  detail::PairKeys keys;
  // The collisions of the last call (kept with their keys for a re-test) and the candidate counts of that call.
  detail::SortedRecords<Collision> collected;
  detail::StageCounts counts;
  // The cloth positions of this call, copied from the caller's (any layout) into the row-major layout the
  // hierarchies and the pair blocks read: the one copy detect() makes. With DetectorSettings::reuse_unchanged they
  // go to the re-test cache when the call completes (a swap, not a copy).
  Vertices current_start, current_end;
  detail::RetestCache retest;
  DetectionStats stats;
  // The state of the last state query (the cloth's positions, copied as detect() copies a step's) and the pairs of
  // the last proximity() call.
  Vertices state_positions;
  detail::SortedRecords<Proximity> proximities;
  detail::SortedRecords<FaceIntersection> intersecting;  // the faces of the last intersections() call

  // Whether a re-test may keep the last call's answer: enabled, no culler (its answer is not a function of the pair
  // alone), and no obstacle changed since. A moving obstacle is stale again after every call, so its steps are always
  // searched in full.
  [[nodiscard]] bool may_reuse() const { return plan.settings.reuse_unchanged && !plan.culler; }

  // What the stream reads for a search with the cloth at `start`/`end`, and the pairs' keys.
  void prepare(const Vertices& start, const Vertices& end) {
    frames = bodies.frames(start, end);
    keys.assign(frames);
  }

  // The limits of a search that keeps records: the cancel check and the collision budget.
  [[nodiscard]] detail::StreamLimits budgeted() const { return {&cancel, plan.settings.max_collisions}; }

  // The candidate search on the frames of prepare(), every block handed to `stage` (begun by the caller) as it is
  // found; with `only_moved`, just the pairs with a cloth vertex the re-test cache flags as moved. `kept` records of
  // the call are already found. Adds the candidate counts to `found` and the search's time summed over its tasks to
  // `task_ms`. Throws CollisionBudgetExceeded when the records exceed the limits' budget, DetectionCancelled when the
  // cancel check says so.
  void search(detail::PairStage& stage, const detail::StreamLimits& limits, long kept, bool only_moved,
              detail::StageCounts& found, double& task_ms) {
    stream.begin(frames, keys, limits, stage, kept);
    broadphase::TraversalSettings traversal = plan.traversal;
    traversal.moved_vertices = only_moved ? &retest.moved() : nullptr;
    broadphase::TraversalStats traversal_stats;
    const broadphase::BodyView cloth_view = bodies.cloth_view();
    if (plan.settings.self_collision) broadphase::find_self_candidates(cloth_view, traversal, stream, &traversal_stats);
    for (int body = 1; body <= bodies.obstacle_count(); ++body) {
      broadphase::find_pair_candidates(cloth_view, bodies.obstacle_view(body), traversal, stream, &traversal_stats);
    }
    task_ms += traversal_stats.task_ms;
    stream.take_candidate_counts(found.vertex_face, found.edge_edge, found.face_face);
  }

  // The candidate search of a state query: the state hierarchies of DetectorBodies::refit_state, the stream's frames
  // those of DetectorBodies::state_frames, `traversal` the search's settings, `limits` the stream's. Otherwise as
  // search().
  void search_state(detail::PairStage& stage, const broadphase::TraversalSettings& traversal,
                    const detail::StreamLimits& limits, detail::StageCounts& found, double& task_ms) {
    stream.begin(frames, keys, limits, stage, 0);
    broadphase::TraversalStats traversal_stats;
    const broadphase::BodyView cloth_view = bodies.cloth_state_view();
    if (plan.settings.self_collision) broadphase::find_self_candidates(cloth_view, traversal, stream, &traversal_stats);
    for (int body = 1; body <= bodies.obstacle_count(); ++body) {
      broadphase::find_pair_candidates(cloth_view, bodies.obstacle_state_view(body), traversal, stream,
                                       &traversal_stats);
    }
    task_ms += traversal_stats.task_ms;
    stream.take_candidate_counts(found.vertex_face, found.edge_edge, found.face_face);
  }

  // Starts a call of `caller` (its name for the messages): checks the cloth positions, copies them into
  // current_start / current_end and clears the stats.
  void begin_call(const PositionsRef& caller_start, const PositionsRef& caller_end, const std::string& caller) {
    const int vertex_count = bodies.cloth().topology.vertex_count;
    detail::check_positions(caller_start, vertex_count, caller + ": cloth start positions");
    detail::check_positions(caller_end, vertex_count, caller + ": cloth end positions");
    current_start = caller_start;
    current_end = caller_end;
    stats = DetectionStats{};
  }

  // Forgets a call that threw: no collisions, no search state, nothing a re-test could reuse.
  void discard() {
    collected.clear();
    stream.discard();
    step_stage.discard();
    earliest_stage.discard();
    counts = detail::StageCounts{};
    retest.forget();
  }

  // Refits the state hierarchies to state_positions (no inflation: touching faces have touching boxes) and runs the
  // face search into the intersection stage with `limits` (a search ended by StreamLimits::stop_at returns
  // normally). Sets the refit time; adds the search's counts, its wall time and its tasks' time.
  void search_intersections(const detail::StreamLimits& limits, detail::StageCounts& found, double& wall_ms,
                            double& task_ms);

  // Starts a state query of `caller` (its name for the messages): checks the cloth positions, copies them into
  // state_positions and clears the stats. The step's state (its positions, records and re-test cache) is untouched.
  void begin_state_call(const PositionsRef& positions, const std::string& caller) {
    detail::check_positions(positions, bodies.cloth().topology.vertex_count, caller + ": cloth positions");
    state_positions = positions;
    stats = DetectionStats{};
  }
};

}  // namespace clothcd
