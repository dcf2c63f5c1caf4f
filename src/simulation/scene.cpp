// The paper's scenes (Jin et al., section 4.5): (1) a cloth falls on a box and rests on it; (2) a cloth covers a
// character with sharp edges; (3) a moving human passes under a falling cloth, which ends up on it; plus one drop per
// model of Tables 3-5. Every obstacle is scaled to a 1 m extent and the 1.6 m cloth starts just above it.
#include "clothcd/simulation/scene.hpp"

#include <stdexcept>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"

namespace clothcd::simulation {
namespace {

constexpr double kClothSize = 1.6;
constexpr double kDropHeight = 0.06;

/// A catalog model and the axis that points up in its file.
struct ModelScene {
  const char* scene;
  const char* model;
  int up;
};

constexpr ModelScene kModelScenes[] = {
    {"character", "human-blend", 2}, {"rabbit", "rabbit", 1}, {"cat", "cat", 1},     {"dinosaur", "dinosaur", 1},
    {"human", "human-blend", 2},     {"bird", "bird", 1},     {"sphere", "sphere", 1}, {"cube", "cube", 1},
    {"fish", "fish", 1},
};

TriangleMesh load_obstacle_file(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    throw std::invalid_argument("model file " + path.string() + " does not exist");
  }
  return load_mesh(path);
}

TriangleMesh load_model(const std::string& model, const SceneSettings& settings) {
  const std::filesystem::path dir = settings.model_dir.empty() ? default_model_dir() : settings.model_dir;
  return load_obstacle_file(fetch_model(model, dir));
}

TriangleMesh make_cloth(const SceneSettings& settings, double height) {
  TriangleMesh cloth;
  if (settings.resolution >= 0) {
    if (settings.resolution < 2 || settings.resolution > kMaxResolution) {
      throw std::invalid_argument("cloth resolution must be 2 to " + std::to_string(kMaxResolution) +
                                  " vertices per side (got " + std::to_string(settings.resolution) + ")");
    }
    cloth = make_grid(settings.resolution, settings.resolution, kClothSize, kClothSize);
  } else {
    cloth = make_paper_cloth(settings.cloth, kClothSize);
  }
  cloth.vertices.col(1).array() += height;
  return cloth;
}

Scene drop_on(const std::string& name, TriangleMesh obstacle, const SceneSettings& settings) {
  Scene scene;
  scene.name = name;
  const double top = obstacle.vertices.col(1).maxCoeff();
  scene.cloth = make_cloth(settings, top + kDropHeight);
  scene.obstacles.push_back({name, std::move(obstacle), {}});
  return scene;
}

Scene make_walker(const SceneSettings& settings) {
  TriangleMesh body = normalize_obstacle(load_model("human-blend", settings), 2, 1.0);
  constexpr int kWalkSteps = 100;
  constexpr double kStart = -0.9;
  body.vertices.col(0).array() += kStart;
  Scene scene;
  scene.name = "walker";
  scene.cloth = make_cloth(settings, body.vertices.col(1).maxCoeff() + 0.5);
  RigidMotion walk;
  walk.translation = Eigen::Vector3d(-kStart / kWalkSteps, 0.0, 0.0);
  walk.axis = Eigen::Vector3d::UnitY();
  walk.angle = 0.002;  // a slight turn while walking, about 11 degrees in all
  walk.pivot = Eigen::Vector3d(kStart, 0.0, 0.0);
  walk.moving_steps = kWalkSteps;
  scene.obstacles.push_back({"human-blend", std::move(body), walk});
  scene.default_steps = 300;
  return scene;
}

}  // namespace

const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names = {"box",  "character", "walker", "rabbit", "cat",  "dinosaur",
                                                 "human", "bird",     "sphere", "cube",   "fish", "file"};
  return names;
}

Scene make_scene(const SceneSettings& settings) {
  if (settings.name == "box") {
    TriangleMesh box = make_box(Eigen::Vector3d(0.4, 0.25, 0.3));
    box.vertices.col(1).array() += 0.25;
    return drop_on("box", std::move(box), settings);
  }
  if (settings.name == "walker") return make_walker(settings);
  if (settings.name == "file") {
    if (settings.model_file.empty()) throw std::invalid_argument("scene 'file' needs a model file");
    return drop_on("file", normalize_obstacle(load_obstacle_file(settings.model_file), 1, 1.0), settings);
  }
  for (const ModelScene& m : kModelScenes) {
    if (settings.name == m.scene) return drop_on(m.scene, normalize_obstacle(load_model(m.model, settings), m.up), settings);
  }
  std::string known;
  for (const std::string& n : scene_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown scene '" + settings.name + "' (known: " + known + ")");
}

}  // namespace clothcd::simulation
