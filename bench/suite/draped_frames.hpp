#pragma once
/// @file
/// Detector frames of a cloth draping over a model: a simulation scene run for some steps, the last ones kept as the
/// detector sees them (the cloth at the start of the step and its free-flight end, before any response).
#include <string>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"
#include "clothcd/simulation/simulator.hpp"

namespace clothcd::bench {

/// One step of the detector's view: the cloth at the start of the step and its free-flight end.
struct Frame {
  Vertices start;  ///< Cloth positions at the start of the step.
  Vertices end;    ///< Cloth positions at the end of the step without collision response.
};

/// A simulated scene and the detector frames of its draping phase.
struct DrapedCase {
  std::string model;                          ///< Scene name (the model the cloth falls on).
  char cloth = 'B';                           ///< The paper's cloth letter.
  TriangleMesh cloth_rest;                    ///< The cloth's topology (and rest pose).
  TriangleMesh obstacle;                      ///< The model, static.
  std::vector<Frame> frames;                  ///< The last frames of the run.
  std::vector<simulation::StepStats> steps;   ///< Statistics of every simulated step.
};

/// Runs scene `model` with cloth `cloth` for `steps` steps at the scene's default step and keeps the last `frames`
/// frames; models come from `model_dir`.
[[nodiscard]] DrapedCase simulate_draping(const std::string& model, char cloth, int steps, int frames,
                                          const std::string& model_dir);

}  // namespace clothcd::bench
