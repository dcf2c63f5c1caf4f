// Short runs of every scene with cloth A: no intersecting triangle pair at the end of any step (checked by the
// independent frame check), the same hash on a repeated run, and clear errors on bad input.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "clothcd/simulation/intersection_check.hpp"
#include "clothcd/simulation/simulator.hpp"

using namespace clothcd;
using namespace clothcd::simulation;

namespace {

std::filesystem::path test_model_dir() { return std::filesystem::temp_directory_path() / "clothcd-test-models"; }

Scene scene_named(const std::string& name) {
  SceneSettings settings;
  settings.name = name;
  settings.cloth = 'A';
  settings.model_dir = test_model_dir();
  return make_scene(settings);
}

/// Runs `steps` steps and checks every step's end state; returns how many steps touched the obstacle (within 1 cm).
int run_without_intersections(const Scene& scene, int steps, const SimulationSettings& settings = {}) {
  Simulator sim(scene, settings);
  int touching = 0;
  for (int s = 0; s < steps; ++s) {
    const StepStats stats = sim.step();
    CHECK(stats.settled);
    const IntersectionReport report = check_frame(sim.model().rest.faces, sim.state().positions, sim.obstacle_meshes());
    INFO(scene.name << " step " << s);
    REQUIRE(report.cloth_cloth_pairs == 0);
    REQUIRE(report.cloth_obstacle_pairs == 0);
    touching += report.min_cloth_obstacle_distance < 0.01;
  }
  return touching;
}

}  // namespace

TEST_CASE("box scene: the cloth lands on the box without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("box"), 40) > 0);
}

TEST_CASE("box scene with the AABB hierarchy, filters and no culling", "[simulation][scene]") {
  SimulationSettings settings;
  settings.detector.hierarchy = HierarchyKind::Aabb;
  settings.detector.culling = GENERATE(CullingMode::None, CullingMode::Filters);
  CHECK(run_without_intersections(scene_named("box"), 28, settings) > 0);
}

TEST_CASE("box scene with the AABB-OBB hierarchy, filters and no culling", "[simulation][scene]") {
  SimulationSettings settings;
  settings.detector.hierarchy = HierarchyKind::AabbObb;
  settings.detector.culling = GENERATE(CullingMode::None, CullingMode::Filters);
  CHECK(run_without_intersections(scene_named("box"), 28, settings) > 0);
}

TEST_CASE("box scene with the sphere-root-AABB hierarchy and each filter alone", "[simulation][scene]") {
  SimulationSettings settings;
  settings.detector.culling = GENERATE(CullingMode::NonPenetration, CullingMode::Projection);
  CHECK(run_without_intersections(scene_named("box"), 28, settings) > 0);
}

TEST_CASE("human scene with and without the contact memory", "[simulation][scene]") {
  SimulationSettings settings;
  settings.response.contact_reach = GENERATE(0.0, 4.0);
  CHECK(run_without_intersections(scene_named("human"), 60, settings) > 0);
}

TEST_CASE("character scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("character"), 28) > 0);
}

TEST_CASE("sphere scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("sphere"), 28) > 0);
}

TEST_CASE("cube scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("cube"), 28) > 0);
}

TEST_CASE("fish scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("fish"), 28) > 0);
}

TEST_CASE("bird scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("bird"), 28) > 0);
}

TEST_CASE("dinosaur scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("dinosaur"), 28) > 0);
}

TEST_CASE("cat scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("cat"), 28) > 0);
}

TEST_CASE("human scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("human"), 28) > 0);
}

TEST_CASE("rabbit scene: the cloth reaches the model without intersecting", "[simulation][scene]") {
  CHECK(run_without_intersections(scene_named("rabbit"), 28) > 0);
}

TEST_CASE("walker scene: the walking body reaches the falling cloth without intersecting it", "[simulation][scene]") {
  // The body walks under the falling cloth for 100 steps; the cloth comes within 1 cm of it in the first 160.
  CHECK(run_without_intersections(scene_named("walker"), 160) > 0);
}

TEST_CASE("the same run gives the same state hash", "[simulation][determinism]") {
  const Scene scene = scene_named("sphere");
  auto run = [&](int steps) {
    Simulator sim(scene);
    for (int s = 0; s < steps; ++s) sim.step();
    return sim.state_hash();
  };
  const auto first = run(26);
  CHECK(run(26) == first);
  CHECK(run(25) != first);
}

TEST_CASE("bad simulation input fails with a clear message", "[simulation][bad-input]") {
  const Scene scene = scene_named("box");
  for (const double dt : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(), 1.5, 1e10,
                          std::numeric_limits<double>::infinity()}) {
    SimulationSettings settings;
    settings.dt = dt;
    CHECK_THROWS_WITH(Simulator(scene, settings), Catch::Contains("dt"));
  }
  for (const double reach : {-1.0, std::numeric_limits<double>::infinity()}) {
    SimulationSettings settings;
    settings.response.contact_reach = reach;
    CHECK_THROWS_WITH(Simulator(scene, settings), Catch::Contains("contact_reach"));
  }
  for (const double separation : {std::numeric_limits<double>::quiet_NaN(), 0.5, 1e300}) {
    SimulationSettings settings;
    settings.response.separation = separation;  // NaN reached detect() as NaN positions
    CHECK_THROWS_WITH(Simulator(scene, settings), Catch::Contains("separation"));
  }
  for (const IntegratorSettings integrator : {IntegratorSettings{0, 1e-3}, IntegratorSettings{-5, 1e-3},
                                              IntegratorSettings{20, std::numeric_limits<double>::quiet_NaN()},
                                              IntegratorSettings{20, 0.0}}) {
    SimulationSettings settings;
    settings.integrator = integrator;  // each froze the cloth before: no CG iteration ran
    CHECK_THROWS_WITH(Simulator(scene, settings), Catch::Contains("cg_"));
  }
  SceneSettings zero;
  zero.name = "box";
  zero.resolution = 0;
  CHECK_THROWS_WITH(make_scene(zero), Catch::Contains("resolution"));
  SceneSettings huge = zero;  // would not fit in memory: refused before allocating
  huge.resolution = 100000;
  CHECK_THROWS_WITH(make_scene(huge), Catch::Contains("resolution") && Catch::Contains("2048"));
  // A thickness near the edge length makes every primitive touch its neighbours' neighbours at rest: refused with
  // advice instead of running out of memory (300 x 300 vertices on the 1.6 m cloth: 5.4 mm edges, 4 mm thickness).
  SceneSettings fine = zero;
  fine.resolution = 300;
  const Scene dense = make_scene(fine);
  CHECK_THROWS_WITH(Simulator(dense, SimulationSettings{}), Catch::Contains("thickness") && Catch::Contains("median edge"));
  SimulationSettings thinner;
  thinner.response.thickness = 0.002;
  CHECK_NOTHROW(Simulator(dense, thinner));
  SceneSettings unknown;
  unknown.name = "teapot";
  CHECK_THROWS_WITH(make_scene(unknown), Catch::Contains("unknown scene 'teapot'"));
  SceneSettings cloth_d;
  cloth_d.cloth = 'D';
  CHECK_THROWS_WITH(make_scene(cloth_d), Catch::Contains("cloth"));

  SceneSettings missing;
  missing.name = "file";
  missing.model_file = std::filesystem::temp_directory_path() / "clothcd-no-such-model.obj";
  CHECK_THROWS_WITH(make_scene(missing), Catch::Contains("does not exist"));

  const auto nan_model = std::filesystem::temp_directory_path() / "clothcd-nan-model.obj";
  std::ofstream(nan_model) << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  SceneSettings with_nan;
  with_nan.name = "file";
  with_nan.model_file = nan_model;
  CHECK_THROWS_WITH(make_scene(with_nan), Catch::Contains("clothcd-nan-model.obj"));
}

TEST_CASE("clothcd simulate rejects dt = 0 and a negative contact reach with a one-line message",
          "[simulation][cli][bad-input]") {
  const auto dir = std::filesystem::temp_directory_path() / "clothcd-simulate-bad";
  const auto err = dir.string() + ".err";
  using OptionAndWord = std::pair<std::string, std::string>;
  const OptionAndWord cases[] = {{"--dt 0", "dt"}, {"--dt 1e10", "dt"}, {"--contact-reach -1", "contact_reach"}};
  for (const auto& [option, word] : cases) {
    const std::string command = std::string(CLOTHCD_CLI_PATH) + " simulate --scene box " + option + " --out " +
                                dir.string() + " > /dev/null 2> " + err;
    CHECK(std::system(command.c_str()) != 0);
    std::ifstream in(err);
    std::stringstream text;
    text << in.rdbuf();
    CHECK_THAT(text.str(), Catch::Contains("clothcd: error:") && Catch::Contains(word));
  }
}
