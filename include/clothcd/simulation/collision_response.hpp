#pragma once
/// @file
/// Collision response for one step, in two stages (Bridson, Fedkiw and Anderson 2002, "Robust treatment of collisions,
/// contact and friction for cloth animation", section 7, with a simpler last resort than its impact zones):
///  1. inelastic position impulses with Coulomb friction on every collision the detector reports, Gauss-Seidel style,
///     pushing each pair apart along its contact normal to a little more than the thickness;
///  2. when a few rounds of detection + impulses leave collisions, the fail-safe: the cloth vertices of every remaining
///     collision stop moving relative to the body they touch (kept at their start-of-step position, or carried rigidly
///     with the moving obstacle). Vertices only ever go free -> static -> carried, so the loop ends; a pair whose
///     vertices all move by one rigid motion keeps its start-of-step (intersection-free) configuration up to an
///     invertible affine map, so it cannot cross during the step.

#include <algorithm>
#include <vector>

#include "clothcd/detection/collision.hpp"
#include "clothcd/simulation/cloth_model.hpp"
#include "clothcd/simulation/obstacle.hpp"

namespace clothcd::simulation {

/// Settings of the response.
struct ResponseSettings {
  double thickness = 0.004;    ///< Minimum separation the impulses restore, scene units (also the detector's).
  double separation = 1.25;    ///< Impulses push a pair to separation * thickness (1..100), so it is not reported again at once.
  double friction = 0.3;       ///< Coulomb friction coefficient.
  int impulse_rounds = 4;      ///< Detection + impulse rounds before the fail-safe.
  int failsafe_rounds = 64;    ///< Upper bound on fail-safe rounds (each one detection call).
  /// Contacts of earlier steps are re-applied as impulses before the next step's detection while their gap at the
  /// start of the step is at most contact_reach * thickness (ContactMemory); 0 turns the memory off.
  double contact_reach = 4.0;
};

/// Everything the response reads about one step of one scene.
struct StepContext {
  const ClothModel* model = nullptr;                    ///< The cloth (masses, pinned flags).
  const Vertices* cloth_start = nullptr;                ///< Cloth positions at the start of the step (#V x 3).
  const std::vector<Obstacle>* obstacles = nullptr;     ///< The obstacles (body k is obstacles[k - 1]).
  const std::vector<Vertices>* obstacle_start = nullptr;  ///< Obstacle positions at the start of the step, one per body.
  const std::vector<Vertices>* obstacle_end = nullptr;  ///< Obstacle positions at the end of the step, one per body.
  int step = 0;                                         ///< Index of the step (for the obstacles' motion).
};

/// Removes the detector's conservative reports (pairs it could not decide) that a distance bound proves apart, and
/// gives the remaining conservative ones usable contact data. The bound: with d0 and d1 the primitives' distances at the
/// start and end of the step and m the largest relative displacement of a vertex of one against a vertex of the other,
/// the distance never drops below (d0 + d1 - m) / 2 during the step (distance is 1-Lipschitz in the motion). Pairs
/// whose bound exceeds `thickness` cannot collide; when the whole-step bound is too weak it is applied on 8 equal
/// sub-intervals (m shrinks with their length). Returns how many reports were removed.
int discard_disproved(std::vector<Collision>& collisions, const StepContext& context, const Vertices& cloth_end,
                      double thickness);

/// Gap of a collision's pair along its contact normal at the start of the step: normal . (first point - second point),
/// the points at the collision's parameters. Negative when the pair is on the other side of its normal.
[[nodiscard]] double start_gap(const Collision& collision, const StepContext& context);

/// Applies one Gauss-Seidel sweep of impulses for `collisions` (in their given order) to the cloth's end-of-step
/// positions `cloth_end` (#V x 3). Obstacles and pinned vertices do not move. Throws std::invalid_argument for a
/// collision naming a body or vertex that does not exist.
void apply_impulses(const std::vector<Collision>& collisions, const StepContext& context,
                    const ResponseSettings& settings, Vertices& cloth_end);

/// The fail-safe's bookkeeping: per cloth vertex, free (-1), static (0) or carried by obstacle body k (k >= 1).
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class FailSafe {
 public:
  /// Starts with every vertex of a `vertex_count`-vertex cloth free (a negative count is an empty cloth).
  explicit FailSafe(int vertex_count) : group_(static_cast<std::size_t>(std::max(vertex_count, 0)), -1) {}

  /// Puts the cloth vertices of every collision into the group that stops their relative motion; returns how many
  /// vertices changed group (0 means the fail-safe has settled). Throws std::invalid_argument for a collision naming a
  /// body or vertex that does not exist.
  int absorb(const std::vector<Collision>& collisions, const StepContext& context);

  /// Overwrites `cloth_end` for every grouped vertex: static ones at their start position, carried ones moved with
  /// their obstacle.
  void apply(const StepContext& context, Vertices& cloth_end) const;

  /// Number of vertices that are not free.
  [[nodiscard]] int grouped_vertices() const;

 private:
  std::vector<int> group_;
};

/// Sorts collisions into a canonical order (kind, then vertex references, then toi) so that the response does not
/// depend on the detector's output order.
void sort_collisions(std::vector<Collision>& collisions);

}  // namespace clothcd::simulation
