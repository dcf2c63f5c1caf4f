#pragma once
// The detector's bodies (internal): the cloth (body 0) and the obstacles (1, 2, ...), each with its topology, its
// positions over the coming step, its swept vertex boxes and its hierarchy, refitted before a search only where
// something changed.
#include <cstdint>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/swept_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "pair_stream.hpp"

namespace clothcd::detail {

/// One body: topology, positions over the coming step, swept vertex boxes and hierarchy.
struct Body {
  broadphase::BodyTopology topology;  ///< Faces and edges.
  Vertices rest;                      ///< Obstacles: the mesh as added.
  Vertices start;                     ///< Obstacles: positions at the start of the coming step.
  Vertices end;                       ///< Obstacles: positions at its end.
  broadphase::SweptBoxes boxes;       ///< Vertex boxes only (compute_swept_vertex_boxes): the hierarchy makes the rest.
  broadphase::Bvh bvh;                ///< Hierarchy over `boxes`.
  bool stale = true;                  ///< Boxes and hierarchy must be recomputed before the next search.
  bool moving = false;                ///< Positions were set for the coming step only.
  /// The queries of one state: the vertex boxes of the positions at one instant and their own hierarchy, so that a
  /// state query never disturbs the step's boxes and hierarchy (which a re-test of the step reuses).
  broadphase::SweptBoxes state_boxes;
  broadphase::Bvh state_bvh;          ///< Hierarchy over `state_boxes`.
};

/// The cloth and the obstacles of a detector.
class DetectorBodies {
 public:
  /// The cloth's topology; its hierarchy is built with `cloth_hierarchy`, the obstacles' with the same settings but
  /// `obstacle_volume`.
  DetectorBodies(const Faces& cloth_faces, int cloth_vertex_count, const broadphase::BvhSettings& cloth_hierarchy,
                 broadphase::VolumeKind obstacle_volume);

  /// Adds a static obstacle; returns its body id (1, 2, ...). Throws std::invalid_argument on a non-finite coordinate.
  int add_obstacle(const TriangleMesh& mesh);
  /// Obstacle `body` (1 .. obstacle_count()); throws std::invalid_argument naming `caller` otherwise.
  Body& obstacle(int body, const char* caller);
  /// The same, read only.
  const Body& obstacle(int body, const char* caller) const;
  /// Number of obstacles.
  [[nodiscard]] int obstacle_count() const { return static_cast<int>(obstacles_.size()); }
  /// The cloth.
  [[nodiscard]] const Body& cloth() const { return cloth_; }
  /// True when some obstacle changed since the last refit.
  [[nodiscard]] bool any_obstacle_stale() const;

  /// Recomputes the cloth's boxes and refits its hierarchy to `start`/`end` (only the vertices flagged in `moved` when
  /// given: the others are where the last refit saw them), and does the same for the stale obstacles. Returns how many
  /// hierarchies were rebuilt instead of refitted.
  int refit(const Vertices& start, const Vertices& end, double thickness, const std::vector<std::uint8_t>* moved);

  /// refit() over the part [from, to] of the step only (0 <= from < to <= 1; broadphase::compute_part_vertex_boxes):
  /// the cloth and the moving obstacles get the boxes of their motion over t in [from, to]; a resting obstacle's
  /// boxes are the same for every part. Moving obstacles stay stale (their boxes are not the whole step's). Returns how
  /// many hierarchies were rebuilt instead of refitted.
  int refit_part(const Vertices& start, const Vertices& end, double from, double to, double thickness);

  /// Refits the state hierarchies to one state: the cloth at `positions`, each obstacle at its positions at the start
  /// of the coming step, every vertex box inflated by half of `distance` (>= 0) on every side, so that primitives
  /// closer than `distance` have overlapping boxes. Returns how many hierarchies were rebuilt instead of refitted.
  int refit_state(const Vertices& positions, double distance);
  /// The cloth's view for a search of the state of refit_state().
  [[nodiscard]] broadphase::BodyView cloth_state_view() const;
  /// Obstacle `body`'s view for a search of the state of refit_state().
  [[nodiscard]] broadphase::BodyView obstacle_state_view(int body) const;
  /// What the stream reads for a state query, per body id: the cloth at `positions`, the obstacles at the start of
  /// the coming step, as both ends of a step of zero length.
  [[nodiscard]] std::vector<BodyFrames> state_frames(const Vertices& positions) const;

  /// What the pair stream reads, per body id, with the cloth at `start`/`end` (valid while those and the bodies are).
  [[nodiscard]] std::vector<BodyFrames> frames(const Vertices& start, const Vertices& end) const;
  /// The cloth's view for the candidate search.
  [[nodiscard]] broadphase::BodyView cloth_view() const;
  /// Obstacle `body`'s view for the candidate search.
  [[nodiscard]] broadphase::BodyView obstacle_view(int body) const;

  /// Ends a step: an obstacle moved for it rests at its end positions from the next step on, unless moved again.
  void finish_step();

 private:
  // The index in obstacles_ of obstacle `body`; throws std::invalid_argument naming `caller` when there is none.
  [[nodiscard]] std::size_t obstacle_index(int body, const char* caller) const;

  broadphase::BvhSettings bvh_settings_;  // the cloth's (an obstacle's differs only in its volume)
  broadphase::VolumeKind obstacle_volume_;
  Body cloth_;
  std::vector<Body> obstacles_;
};

}  // namespace clothcd::detail
