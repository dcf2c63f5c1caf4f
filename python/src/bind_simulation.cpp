// Cloth simulation for Python: a cloth mesh dropped on obstacle meshes, or one of the paper's scenes; the frames come
// back as (N, 3) arrays. The steps run without the GIL.
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "clothcd/simulation/scene.hpp"
#include "clothcd/simulation/simulator.hpp"

namespace clothcd::python {
namespace {

using MeshInput = std::tuple<DoubleArray, IntArray>;

std::vector<nb::ndarray<nb::numpy, double>> run(const simulation::Scene& scene, int steps, int frames_every,
                                                double dt, double thickness, const std::string& culling,
                                                const std::string& model_path) {
  if (steps < 0) throw std::invalid_argument("simulate: steps must be >= 0");
  if (frames_every < 1) throw std::invalid_argument("simulate: frames_every must be >= 1");
  simulation::SimulationSettings settings;
  settings.dt = dt;
  settings.response.thickness = thickness;
  if (culling == "filters") {
    settings.detector.culling = CullingMode::Filters;
  } else if (culling == "network") {
    settings.detector.culling = CullingMode::Network;
  } else if (culling == "none") {
    settings.detector.culling = CullingMode::None;
  } else {
    throw std::invalid_argument("simulate: unknown culling '" + culling + "' (filters, network, none)");
  }
  learning::attach_network_culler(settings.detector, model_path);
  std::vector<Vertices> frames;
  {
    nb::gil_scoped_release release;
    simulation::Simulator simulator(scene, settings);
    frames.push_back(simulator.state().positions);
    for (int s = 1; s <= steps; ++s) {
      simulator.step();
      if (s % frames_every == 0) frames.push_back(simulator.state().positions);
    }
  }
  std::vector<nb::ndarray<nb::numpy, double>> result;
  for (const Vertices& frame : frames) result.push_back(matrix_to_numpy(frame));
  return result;
}

}  // namespace

void bind_simulation(nb::module_& m) {
  m.def(
      "simulate",
      [](const MeshInput& cloth, const std::vector<MeshInput>& obstacles, int steps, int frames_every, double dt,
         double thickness, const std::string& culling, const std::string& model_path) {
        simulation::Scene scene;
        scene.name = "python";
        scene.cloth = {to_vertices(std::get<0>(cloth), "cloth vertices"), to_faces(std::get<1>(cloth), "cloth faces")};
        for (const auto& [vertices, faces] : obstacles)
          scene.obstacles.push_back(
              {"obstacle", {to_vertices(vertices, "obstacle vertices"), to_faces(faces, "obstacle faces")}, {}});
        return run(scene, steps, frames_every, dt, thickness, culling, model_path);
      },
      nb::arg("cloth"), nb::arg("obstacles"), nb::kw_only(), nb::arg("steps") = 200, nb::arg("frames_every") = 10,
      nb::arg("dt") = 0.005, nb::arg("thickness") = 0.004, nb::arg("culling") = "filters", nb::arg("model_path") = "",
      "Drops `cloth` = (vertices, faces) under gravity (-y) onto static `obstacles` [(vertices, faces), ...]; returns "
      "the cloth positions of step 0 and every `frames_every`-th step. culling 'network' uses `model_path` (the package's "
      "wrapper passes the shipped model when it is empty).");
  m.def(
      "simulate_scene",
      [](const std::string& name, char cloth, int steps, int frames_every, double dt, double thickness,
         const std::string& culling, const std::string& model_path) {
        simulation::SceneSettings settings;
        settings.name = name;
        settings.cloth = cloth;
        const simulation::Scene scene = simulation::make_scene(settings);
        std::vector<std::tuple<nb::ndarray<nb::numpy, double>, nb::ndarray<nb::numpy, int>>> obstacles;
        for (const simulation::Obstacle& o : scene.obstacles)
          obstacles.emplace_back(matrix_to_numpy(o.rest.vertices), matrix_to_numpy(o.rest.faces));
        return std::make_tuple(matrix_to_numpy(scene.cloth.faces),
                               run(scene, steps < 0 ? scene.default_steps : steps, frames_every, dt, thickness, culling,
                                   model_path),
                               obstacles);
      },
      nb::arg("name"), nb::arg("cloth") = 'A', nb::kw_only(), nb::arg("steps") = -1, nb::arg("frames_every") = 10,
      nb::arg("dt") = 0.005, nb::arg("thickness") = 0.004, nb::arg("culling") = "filters", nb::arg("model_path") = "",
      "One of the paper's scenes (box, sphere, ...; the models come from the Debian packages of "
      "scripts/install-deps.sh): returns (cloth faces, frames, obstacles at rest [(vertices, faces), ...]); steps < 0 "
      "takes the scene's default.");
}

}  // namespace clothcd::python
