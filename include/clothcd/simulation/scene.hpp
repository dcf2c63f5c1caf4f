#pragma once
/// @file
/// The paper's simulation scenes (section 4.5 and Tables 3-5): a square cloth dropped on a box, on a sharp-edged
/// character, on a walking human, and on each model of the paper's tables.

#include <filesystem>
#include <string>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"
#include "clothcd/simulation/obstacle.hpp"

namespace clothcd::simulation {

/// Largest cloth resolution (vertices per side) a scene accepts: 2048^2 vertices, about 8.4M triangles.
inline constexpr int kMaxResolution = 2048;

/// What to build.
struct SceneSettings {
  std::string name = "box";           ///< One of scene_names().
  char cloth = 'A';                   ///< The paper's cloth: 'A' (20x20), 'B' (30x30) or 'C' (50x50).
  int resolution = -1;                ///< When >= 0: an N x N cloth instead of the letter (2 <= N <= kMaxResolution).
  std::filesystem::path model_dir;    ///< Cache folder for fetch_model (empty: default_model_dir()).
  std::filesystem::path model_file;   ///< Scene "file": the obstacle mesh to drop the cloth on.
};

/// A ready-to-run scene in SI units (metres): obstacles normalised to a 1 m extent, the cloth 1.6 m square above them.
struct Scene {
  std::string name;                 ///< Scene name.
  TriangleMesh cloth;               ///< The cloth at rest, in its initial pose.
  std::vector<int> pinned;          ///< Pinned cloth vertices (none in the paper's scenes).
  std::vector<Obstacle> obstacles;  ///< Obstacles, body k = obstacles[k - 1].
  int default_steps = 200;          ///< Steps the scene needs to settle at the default step.
  double default_dt = 0.005;        ///< Default step, seconds.
};

/// Every scene name: box, character, walker, rabbit, cat, dinosaur, human, bird, sphere, cube, fish, file.
[[nodiscard]] const std::vector<std::string>& scene_names();

/// Builds a scene. Throws std::invalid_argument on an unknown scene or cloth, a resolution below 2, or a missing
/// model file; MeshError (naming the file) when a model cannot be read or holds NaN / infinite coordinates.
[[nodiscard]] Scene make_scene(const SceneSettings& settings);

}  // namespace clothcd::simulation
