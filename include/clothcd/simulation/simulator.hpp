#pragma once
/// @file
/// The simulation loop: forces and implicit integration, continuous collision detection by clothcd::CollisionDetector,
/// impulses and the fail-safe, step after step; every step ends without intersections.

#include <cstdint>
#include <memory>
#include <vector>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/simulation/cloth_model.hpp"
#include "clothcd/simulation/collision_response.hpp"
#include "clothcd/simulation/contact_memory.hpp"
#include "clothcd/simulation/implicit_integrator.hpp"
#include "clothcd/simulation/scene.hpp"

namespace clothcd::simulation {

/// Longest time step a simulation accepts, seconds: far beyond any useful cloth step (the paper's is 5 ms), while
/// absurd steps (1e10 s) are refused instead of sending the cloth to 1e12 m.
inline constexpr double kMaxTimeStep = 1.0;

/// Everything that tunes a run.
struct SimulationSettings {
  double dt = 0.005;                 ///< Step, seconds (0 < dt <= kMaxTimeStep).
  ClothSettings cloth;               ///< Cloth material.
  IntegratorSettings integrator;     ///< Linear solve.
  ResponseSettings response;         ///< Thickness, friction, rounds; its thickness also goes to the detector.
  DetectorSettings detector;         ///< Hierarchy and culling of the detector (its thickness is overwritten).
};

/// Counts and times of one step.
struct StepStats {
  int step = 0;                     ///< Index of the step (0 for the first).
  long candidates = 0;              ///< Candidate pairs after the broad phase, summed over the step's detect() calls.
  long culled = 0;                  ///< Pairs removed by culling, summed over the detect() calls.
  long collisions = 0;              ///< Collisions found by the step's first detect() call.
  int detect_calls = 0;             ///< detect() calls in the step.
  int failsafe_vertices = 0;        ///< Cloth vertices the fail-safe had to stop (0 on a normal step).
  bool settled = true;              ///< False when the last detect() still reported a pair the fail-safe could not fix.
  int cg_iterations = 0;            ///< Conjugate-gradient iterations of the integrator.
  double integration_ms = 0;        ///< Forces + implicit solve, ms.
  double detection_ms = 0;          ///< Time inside detect(), ms.
  double response_ms = 0;           ///< Impulses + fail-safe (outside detect()), ms.
  double step_ms = 0;               ///< Whole step, ms.
};

/// A running simulation of one scene.
/// Threads: step() advances the object's state, so one simulator belongs to one thread at a time; separate simulators
/// may run in parallel.
class Simulator {
 public:
  /// Builds the cloth model and the detector for `scene`. Throws std::invalid_argument on a bad setting (dt <= 0,
  /// negative thickness, ...) or an invalid mesh.
  Simulator(const Scene& scene, const SimulationSettings& settings = {});

  /// Advances one step and returns its statistics.
  StepStats step();

  /// The cloth's current state.
  [[nodiscard]] const ClothState& state() const { return state_; }
  /// The cloth model (topology, masses).
  [[nodiscard]] const ClothModel& model() const { return model_; }
  /// Steps taken so far.
  [[nodiscard]] int steps_taken() const { return step_; }
  /// The obstacles in their current pose, one mesh per obstacle.
  [[nodiscard]] std::vector<TriangleMesh> obstacle_meshes() const;
  /// A 64-bit FNV-1a hash of the cloth's positions and velocities (bit-exact): equal runs give equal hashes.
  [[nodiscard]] std::uint64_t state_hash() const;

 private:
  Scene scene_;
  SimulationSettings settings_;
  ClothModel model_;
  ClothState state_;
  ImplicitIntegrator integrator_;
  CollisionDetector detector_;
  int step_ = 0;
  Vertices start_, end_, velocities_;
  std::vector<Vertices> obstacle_start_, obstacle_end_;
  std::vector<Collision> collisions_;
  ContactMemory contacts_;
};

}  // namespace clothcd::simulation
