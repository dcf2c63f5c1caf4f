#include "draped_frames.hpp"

#include <utility>

#include "clothcd/simulation/scene.hpp"

namespace clothcd::bench {

DrapedCase simulate_draping(const std::string& model, char cloth, int steps, int frames,
                            const std::string& model_dir) {
  simulation::SceneSettings scene_settings;
  scene_settings.name = model;
  scene_settings.cloth = cloth;
  scene_settings.model_dir = model_dir;
  const simulation::Scene scene = simulation::make_scene(scene_settings);
  simulation::SimulationSettings settings;
  settings.dt = scene.default_dt;
  simulation::Simulator simulator(scene, settings);
  DrapedCase c{model, cloth, scene.cloth, scene.obstacles.front().rest, {}, {}};
  const Eigen::RowVector3d fall = settings.dt * settings.dt * settings.cloth.gravity.transpose();
  for (int s = 0; s < steps; ++s) {
    if (s >= steps - frames) {
      const simulation::ClothState& state = simulator.state();
      Frame frame{state.positions, state.positions + settings.dt * state.velocities};
      frame.end.rowwise() += fall;
      c.frames.push_back(std::move(frame));
    }
    c.steps.push_back(simulator.step());
  }
  return c;
}

}  // namespace clothcd::bench
