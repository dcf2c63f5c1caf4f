#pragma once
/// @file
/// The library entry point for a simulation loop: give it the cloth topology and the obstacles once, then per step the
/// cloth positions at the start and end of the step; it returns every colliding vertex-face and edge-edge pair.

#include <Eigen/Geometry>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "clothcd/broadphase/hierarchy_kind.hpp"
#include "clothcd/detection/block_observer.hpp"
#include "clothcd/detection/collision.hpp"
#include "clothcd/detection/detection_errors.hpp"
#include "clothcd/detection/earliest_impact.hpp"
#include "clothcd/detection/face_intersection.hpp"
#include "clothcd/detection/proximity.hpp"
#include "clothcd/mesh/positions_ref.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

class PairCuller;

/// Which culling runs on candidate pairs before the exact CCD.
enum class CullingMode {
  None,            ///< Every candidate goes to the exact CCD.
  NonPenetration,  ///< The algebraic (Bernstein) non-penetration filter.
  Projection,      ///< The spatial linear projection filter.
  Filters,         ///< Both filters, cheaper first: the CCD stage's ccd::CcdFilter::Combined.
  /// A culler in front of the filters, given in DetectorSettings::culler (the learned pair network:
  /// learning::load_network_culler; see detection/pair_culler.hpp): Keep goes to the exact CCD, Check and Drop through
  /// the combined filters as Filters runs them (projection_normals included); a Drop the filters do not confirm goes
  /// to the exact CCD. Culls a subset of Filters.
  Network,
};

/// Largest DetectorSettings::block_pairs.
inline constexpr int kMaxBlockPairs = 1 << 20;

/// Largest DetectorSettings::max_collisions.
inline constexpr long kLargestCollisionBudget = 2'000'000'000;

/// Detector settings; defaults are what a cloth simulation wants.
struct DetectorSettings {
  HierarchyKind hierarchy = HierarchyKind::SphereRootAabb;  ///< Broad phase.
  CullingMode culling = CullingMode::Filters;               ///< Culling before the exact CCD.
  double thickness = 0.0;       ///< Minimum separation (scene units); pairs closer than this count as colliding.
  bool self_collision = true;   ///< Also test the cloth against itself.
  /// The culler of CullingMode::Network (required there, unused otherwise), e.g. the pair network of
  /// learning::load_network_culler. Shared: several detectors may hold the same culler (it is only read).
  std::shared_ptr<const PairCuller> culler;
  /// Triangles per hierarchy leaf (>= 1; median splits make leaves of between half of it and it). 32 since the leaf
  /// tests take eight primitives at a time (the measurement is in the benchmark report's speed targets section).
  int max_leaf_faces = 32;
  double rebuild_ratio = 2.0;   ///< Hierarchy rebuild rule, see broadphase::BvhSettings::rebuild_ratio.
  bool parallel = true;         ///< Use TBB threads (results are identical and in the same order either way).
  /// When detect() is called again with the same start positions (a simulation re-checking its step after collision
  /// response) and unchanged obstacles, search and test again only the pairs with a cloth vertex whose end position
  /// changed, and keep the previous answer for the others (it cannot differ). Not used with CullingMode::Network.
  bool reuse_unchanged = true;
  /// Projection and Filters modes: also project onto the primitives' own directions (face normal, edge cross product)
  /// at the start and end of the step, tried before the paper's five fixed directions, and, for pairs none of those
  /// separates, the in-plane normals of their edges (ccd::ProjectionFilterOptions). Culls far more of a cloth resting
  /// on a surface at the thickness, and the neighbouring pairs of a flat sheet; false gives the paper's filter exactly.
  bool projection_normals = true;
  /// Thickness 0: every pair is decided, so every reported collision is a proven one (true, the default); false is the
  /// approximate mode, which reports the pairs the floating-point fast tier leaves undecided as conservative hits
  /// (ccd::CcdSettings::decide_exactly).
  bool decide_exactly = true;
  /// Candidate pairs each thread holds between the broad phase and the exact test (1 .. kMaxBlockPairs): the search
  /// hands its candidates over in chunks of this many, and each thread culls and tests them in a block of this many
  /// pairs (about 240 bytes each) that it reuses, so memory does not grow with the number of candidates. The result
  /// does not depend on it.
  int block_pairs = 1024;
  /// The collision budget of one detect() call (1 .. kLargestCollisionBudget): a step with more collisions stops its
  /// search as soon as the count passes it and throws CollisionBudgetExceeded (detection_errors.hpp) instead of
  /// filling memory. A degenerate step (a cloth collapsing to a point, a simulation that exploded) has millions; at
  /// the default, the call's result and its sort stay under 450 MB (at most 112 bytes per collision), and a
  /// step of a well-behaved simulation has far fewer (a 146k-face garment in contact: about 107k).
  long max_collisions = 4'000'000;
};

/// Counts and times of the last detect() or earliest_impact() call (earliest_impact: summed over its windows).
struct DetectionStats {
  long candidates_vertex_face = 0;  ///< Candidate pairs after the broad phase.
  long candidates_edge_edge = 0;    ///< Candidate pairs after the broad phase.
  long culled = 0;                  ///< Pairs removed by the culling stage.
  long collisions = 0;              ///< Pairs the exact CCD confirmed.
  double refit_ms = 0;              ///< Time to refit (or rebuild) the hierarchies.
  /// Time to find candidate pairs. The search, the culling and the exact CCD run interleaved (each thread culls and
  /// tests its candidates block by block as it finds them): their wall time is split among the three in proportion to
  /// the threads' time in each.
  double traversal_ms = 0;
  double culling_ms = 0;            ///< Time in the culling stage (see traversal_ms).
  double exact_ms = 0;              ///< Time in the exact CCD (see traversal_ms), sorting the collisions included.
  long network_dropped = 0;         ///< Network mode: pairs the culler dropped and the filters confirmed.
  long network_overruled = 0;       ///< Network mode: drops the filters did not confirm (sent to the exact CCD).
  long network_kept = 0;            ///< Network mode: pairs the culler sent straight to the exact CCD.
  double network_ms = 0;            ///< Network mode: the culler's time (features and inference; part of culling_ms).
  double network_filters_ms = 0;    ///< Network mode: the filters behind the culler (part of culling_ms).
  int rebuilds = 0;                 ///< Hierarchies rebuilt (not just refitted) in this step.
  long reused = 0;                  ///< Pairs whose culling and CCD answer was kept from the previous call.
};

/// Continuous collision detection between a cloth and obstacles, step after step.
/// Threads: one detector belongs to one thread at a time (detect() updates its hierarchies and buffers, and runs TBB
/// threads of its own when DetectorSettings::parallel is set); separate detectors may run in parallel.
class CollisionDetector {
 public:
  /// Takes the cloth's triangles (indices into its `cloth_vertex_count` vertices) and the settings.
  /// Throws std::invalid_argument on out-of-range indices, an empty cloth or Network mode without a culler.
  CollisionDetector(const Faces& cloth_faces, int cloth_vertex_count, const DetectorSettings& settings = {});
  ~CollisionDetector();
  CollisionDetector(CollisionDetector&&) noexcept;             ///< Movable.
  CollisionDetector& operator=(CollisionDetector&&) noexcept;  ///< Movable.

  /// Adds a static obstacle; returns its body id (1, 2, ...). Throws std::invalid_argument on an invalid mesh.
  int add_obstacle(const TriangleMesh& mesh);

  /// Sets the positions of obstacle `body` at the start and end of the next step (a moving obstacle); both #V x 3, in
  /// any layout (PositionsRef), copied once into the detector. After that step the obstacle rests at `end` until set
  /// again. Throws std::invalid_argument on an unknown body, wrong sizes or non-finite coordinates.
  void set_obstacle_positions(int body, const PositionsRef& start, const PositionsRef& end);

  /// Moves obstacle `body` rigidly over the next step: its mesh as added, transformed by `start` and by `end`.
  void set_obstacle_transforms(int body, const Eigen::Isometry3d& start, const Eigen::Isometry3d& end);

  /// Number of obstacles added.
  [[nodiscard]] int obstacle_count() const;

  /// The unique edges of `body` (0 = cloth) as 2 vertex indices each: what Collision::vertices of an edge-edge pair use.
  [[nodiscard]] const std::vector<int>& edges(int body) const;

  /// Finds every collision of the step: cloth positions `start` and `end` (#V x 3 each, finite), in any layout:
  /// Vertices, a column-major Eigen::MatrixXd, an Eigen::Map of one's own buffer (PositionsRef views them in place).
  /// The detector copies each once into its own row-major buffers, the layout its hierarchies and pair blocks read
  /// (the copy it keeps to recognise a re-test of the step, see DetectorSettings::reuse_unchanged); no other copy is
  /// made. The returned reference stays valid until the next call.
  /// Throws std::invalid_argument on wrong sizes or a NaN or infinite coordinate, CollisionBudgetExceeded when the step
  /// has more than DetectorSettings::max_collisions collisions, DetectionCancelled when cancelled (set_cancel_check).
  /// After any of these the detector holds no collisions and stays usable: the next call searches its step in full.
  const std::vector<Collision>& detect(const PositionsRef& start, const PositionsRef& end);

  /// The step's earliest time of impact (see EarliestImpact): how far the cloth can move from `start` towards `end`
  /// (taken as detect() takes them; the obstacles as set for the step) before any pair detect() covers comes into
  /// contact, or within DetectorSettings::thickness. Searches only as much of the step as it needs (consecutive time
  /// windows in time order, up to the first that holds a contact) and tests each pair only up to the earliest contact
  /// found so far, so an early contact costs far less than detect(), and a fast motion's short windows have far fewer
  /// candidates than its whole step. The answer does not depend on the thread count. Like detect(), it ends the step
  /// (a moved obstacle rests at its end afterwards) and throws std::invalid_argument on wrong sizes or non-finite
  /// coordinates, DetectionCancelled when cancelled, and CollisionBudgetExceeded when more than
  /// DetectorSettings::max_collisions pairs of a window come into contact no later than the earliest contact found so
  /// far (a degenerate step: a cloth collapsing to a point touches everywhere at its end, and every such pair must be
  /// examined); the next detect() searches its step in full.
  EarliestImpact earliest_impact(const PositionsRef& start, const PositionsRef& end);

  /// Every pair detect() covers whose distance at one state is below `distance` (scene units): the cloth at
  /// `positions` (#V x 3, finite, in any layout, as detect() takes them), each obstacle at its positions at the start
  /// of the coming step (where it rests unless moved for that step). The pairs are those of detect(): the cloth's own
  /// vertex-face and edge-edge pairs that share no vertex (with DetectorSettings::self_collision) and the cloth
  /// against every obstacle, a vertex against a closed triangle and two closed segments. Membership is exact: a pair
  /// is reported if and only if its distance on the double coordinates, as a real number, is below `distance`
  /// (rounding neither adds nor drops a pair; one at exactly `distance` is not reported). Each record (Proximity)
  /// has the distance within kDistanceRelativeError, the closest points and where they lie; they come in detect()'s
  /// order (vertex-face pairs first, each kind sorted by its primitives). The thickness and the culling mode of the
  /// settings play no part. The returned reference stays valid until the next proximity() call.
  /// Throws std::invalid_argument on wrong sizes, a NaN or infinite coordinate, or a distance that is <= 0, NaN or
  /// infinite; CollisionBudgetExceeded beyond DetectorSettings::max_collisions pairs; DetectionCancelled when
  /// cancelled (set_cancel_check). Afterwards the detector stays usable. A state query leaves the step's hierarchies
  /// and its re-test (DetectorSettings::reuse_unchanged) as they were: a state has hierarchies of its own.
  const std::vector<Proximity>& proximity(const PositionsRef& positions, double distance);

  /// The smallest distance at one state over the pairs proximity() covers (at the same positions), and a pair that
  /// has it: a branch and bound over the hierarchies, which stop descending where the boxes are farther apart than
  /// the closest pair found so far, so no distance has to be guessed. With `upper_bound` (> 0) only pairs closer than
  /// it count, which ends the search sooner; `found` is false when there is none (the default, infinity, finds the
  /// minimum whenever there is a pair). The distance comes with proximity()'s error statement. Throws as proximity()
  /// does (an upper bound that is <= 0 or NaN is invalid).
  MinimumDistance minimum_distance(const PositionsRef& positions,
                                   double upper_bound = std::numeric_limits<double>::infinity());

  /// Every pair of intersecting faces at one state (the positions as proximity() takes them): the cloth's faces
  /// against each other (with DetectorSettings::self_collision) and against every obstacle's, closed triangles, with
  /// the semantics of face_intersection.hpp for faces sharing a vertex or an edge. Decided exactly (orientation signs
  /// by a proven floating-point filter, then exact arithmetic; coplanar overlaps too). Sorted by the first face's
  /// body and index, then the second's. The returned reference stays valid until the next intersections() call.
  /// Throws as proximity() does (CollisionBudgetExceeded beyond DetectorSettings::max_collisions pairs).
  const std::vector<FaceIntersection>& intersections(const PositionsRef& positions);

  /// True when no pair of faces intersects at the state (intersections() would be empty); stops at the first
  /// intersecting pair found. Throws as proximity() does.
  bool is_intersection_free(const PositionsRef& positions);

  /// Counts and times of the last call (detect(), earliest_impact() or a state query; for a state query
  /// candidates are the pairs tested (intersections(): the face pairs, counted as vertex-face), collisions the records
  /// found and exact_ms their exact tests).
  [[nodiscard]] const DetectionStats& stats() const;

  /// Makes later detect() calls cancellable: the call's threads call `cancel` before each block of
  /// DetectorSettings::block_pairs candidate pairs (so from several threads at once: it must be thread-safe, e.g.
  /// reading a std::atomic<bool> another thread sets), and once it returns true the call stops within a block per
  /// thread and throws DetectionCancelled. Its cost is one call per block of about a thousand culled and tested pairs,
  /// nothing beside them. An empty function (the default) turns cancelling off.
  void set_cancel_check(std::function<bool()> cancel);

  /// Shows every later detect() call's candidate pairs to `observer`, block by block, each pair exactly once, with its
  /// culling and exact-test outcome (see ObservedBlock and BlockObserver's thread rule); an empty function stops it.
  /// A re-test call (DetectorSettings::reuse_unchanged) shows only the pairs it searches again: the
  /// DetectionStats::reused pairs keep their last answer and are not shown again. Observing costs a copy of each block.
  void set_block_observer(BlockObserver observer);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace clothcd
