// `clothcd simulate --scene NAME --out DIR`: runs one of the paper's scenes (section 4.5) and writes frames, per-step
// statistics, an independent intersection count per step, rendered pictures and a contact sheet.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/render/rasterizer.hpp"
#include "clothcd/simulation/intersection_check.hpp"
#include "clothcd/simulation/simulator.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

namespace fs = std::filesystem;
using namespace clothcd::simulation;

struct SimulateOptions {
  std::string scene = "box";
  std::string cloth = "A";
  int resolution = -1;
  int steps = -1;
  double dt = Scene{}.default_dt;
  std::string filter = "combined";
  std::string bvh = "sphere-root-aabb";
  int frames_every = 0;
  int check_every = 1;
  double thickness = ResponseSettings{}.thickness;
  double friction = ResponseSettings{}.friction;
  double contact_reach = ResponseSettings{}.contact_reach;
  std::string cache;
  std::string obstacle_file;
  std::string network;
  std::string out;
  bool no_pictures = false;
  bool json = false;
  bool quiet = false;
};

TriangleMesh merge(const std::vector<TriangleMesh>& meshes) {
  TriangleMesh all;
  Eigen::Index v = 0, f = 0;
  for (const TriangleMesh& m : meshes) {
    v += m.vertices.rows();
    f += m.faces.rows();
  }
  all.vertices.resize(v, 3);
  all.faces.resize(f, 3);
  v = f = 0;
  for (const TriangleMesh& m : meshes) {
    all.vertices.middleRows(v, m.vertices.rows()) = m.vertices;
    all.faces.middleRows(f, m.faces.rows()) = m.faces.array() + static_cast<int>(v);
    v += m.vertices.rows();
    f += m.faces.rows();
  }
  return all;
}

std::string numbered(const std::string& stem, int step, const std::string& extension) {
  std::ostringstream name;
  name << stem << '_' << std::setw(4) << std::setfill('0') << step << extension;
  return name.str();
}

struct Pictures {
  render::Camera camera;
  std::vector<render::Image> thumbnails;
  std::vector<std::string> labels;  ///< "STEP N" of each thumbnail.
};

render::Image draw(const Simulator& sim, const Pictures& pictures, int width, int height) {
  const TriangleMesh cloth{sim.state().positions, sim.model().rest.faces};
  const TriangleMesh obstacles = merge(sim.obstacle_meshes());
  render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  return render::render({{&obstacles, {0.62, 0.66, 0.72}}, {&cloth, {0.90, 0.45, 0.20}}}, pictures.camera, settings);
}

void save_frame(const Simulator& sim, const fs::path& out, Pictures* pictures) {
  const int step = sim.steps_taken();
  save_mesh({sim.state().positions, sim.model().rest.faces}, out / "frames" / numbered("cloth", step, ".ply"));
  save_mesh(merge(sim.obstacle_meshes()), out / "frames" / numbered("obstacles", step, ".ply"));
  if (pictures == nullptr) return;
  render::write_png(draw(sim, *pictures, 640, 480), out / "renders" / numbered("frame", step, ".png"));
  pictures->thumbnails.push_back(draw(sim, *pictures, 320, 240));
  pictures->labels.push_back("STEP " + std::to_string(step));
}

render::Camera scene_camera(const Scene& scene) {
  Eigen::Vector3d lo = scene.cloth.vertices.colwise().minCoeff().transpose();
  Eigen::Vector3d hi = scene.cloth.vertices.colwise().maxCoeff().transpose();
  for (const Obstacle& o : scene.obstacles) {
    for (const int s : {0, o.motion.moving_steps}) {
      const Vertices x = o.positions_at(s);
      lo = lo.cwiseMin(x.colwise().minCoeff().transpose());
      hi = hi.cwiseMax(x.colwise().maxCoeff().transpose());
    }
  }
  return render::frame_box(lo, hi);
}

void run(const SimulateOptions& options) {
  if (options.cloth.size() != 1) throw std::invalid_argument("--cloth must be A, B or C");
  check_network_needs_filter(options.network, options.filter);
  create_output_folder(options.out, "--out");
  if (options.frames_every < 0 || options.check_every < 1) {
    throw std::invalid_argument("--frames-every must be >= 0 and --check-every >= 1");
  }
  SceneSettings scene_settings;
  scene_settings.name = options.scene;
  scene_settings.cloth = options.cloth[0];
  scene_settings.resolution = options.resolution;
  scene_settings.model_dir = options.cache;
  scene_settings.model_file = options.obstacle_file;
  const Scene scene = make_scene(scene_settings);

  SimulationSettings settings;
  settings.dt = options.dt;
  settings.response.thickness = options.thickness;
  settings.response.friction = options.friction;
  settings.response.contact_reach = options.contact_reach;
  settings.detector.culling = culling_named(options.filter);
  settings.detector.hierarchy = hierarchy_named(options.bvh);
  learning::attach_network_culler(settings.detector, options.network);
  const int steps = options.steps < 0 ? scene.default_steps : options.steps;
  const int frames_every = options.frames_every > 0 ? options.frames_every : std::max(1, steps / 11);

  Simulator sim(scene, settings);
  const fs::path out = options.out;
  fs::create_directories(out / "frames");
  if (!options.no_pictures) fs::create_directories(out / "renders");
  Pictures pictures{scene_camera(scene), {}, {}};
  Pictures* picture_sink = options.no_pictures ? nullptr : &pictures;

  std::ofstream csv(out / "stats.csv");
  if (!csv) throw std::runtime_error((out / "stats.csv").string() + ": cannot write");
  csv << "step,candidates,culled,collisions,detect_calls,failsafe_vertices,settled,cg_iterations,integration_ms,"
         "detection_ms,response_ms,step_ms,min_cloth_obstacle_distance,cloth_cloth_pairs,cloth_obstacle_pairs\n";
  save_frame(sim, out, picture_sink);

  double detection_total = 0, step_total = 0, response_total = 0;
  long intersecting_steps = 0, failsafe_steps = 0;
  Progress progress("simulating", "steps", options.quiet);
  for (int s = 0; s < steps; ++s) {
    const StepStats st = sim.step();
    detection_total += st.detection_ms;
    step_total += st.step_ms;
    response_total += st.response_ms;
    failsafe_steps += st.failsafe_vertices > 0;
    csv << st.step << ',' << st.candidates << ',' << st.culled << ',' << st.collisions << ',' << st.detect_calls << ','
        << st.failsafe_vertices << ',' << st.settled << ',' << st.cg_iterations << ',' << st.integration_ms << ','
        << st.detection_ms << ',' << st.response_ms << ',' << st.step_ms << ',';
    if (s % options.check_every == 0 || s + 1 == steps) {
      const IntersectionReport check = check_frame(sim.model().rest.faces, sim.state().positions, sim.obstacle_meshes());
      intersecting_steps += check.intersecting_pairs() > 0;
      csv << check.min_cloth_obstacle_distance << ',' << check.cloth_cloth_pairs << ',' << check.cloth_obstacle_pairs;
    } else {
      csv << ",,";
    }
    csv << '\n';
    if (sim.steps_taken() % frames_every == 0 || s + 1 == steps) save_frame(sim, out, picture_sink);
    progress.update(static_cast<std::size_t>(s + 1), static_cast<std::size_t>(steps));
  }
  csv.close();
  if (picture_sink != nullptr) {
    render::write_png(render::contact_sheet(pictures.thumbnails, 4, 4, pictures.labels), out / "contact_sheet.png");
  }

  const double n = std::max(1, steps);
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim.state_hash()));
  if (options.json) {
    Json report = json_report("simulate");
    report["scene"] = scene.name;
    report["cloth_vertices"] = sim.model().vertex_count();
    report["cloth_triangles"] = sim.model().rest.faces.rows();
    report["obstacles"] = scene.obstacles.size();
    report["steps"] = steps;
    report["dt"] = settings.dt;
    report["filter"] = options.filter;
    report["bvh"] = options.bvh;
    report["detection_ms_per_step"] = detection_total / n;
    report["response_ms_per_step"] = response_total / n;
    report["step_ms_per_step"] = step_total / n;
    report["failsafe_steps"] = failsafe_steps;
    report["intersecting_steps"] = intersecting_steps;
    report["output"] = out.string();
    report["state_hash"] = hash;
    print_json(report);
  } else {
    std::cout << "scene:              " << scene.name << " (cloth " << sim.model().vertex_count() << " vertices, "
              << sim.model().rest.faces.rows() << " triangles; " << scene.obstacles.size() << " obstacle(s))\n"
              << "steps:              " << steps << " x " << settings.dt << " s\n"
              << "detection:          " << detection_total / n << " ms/step\n"
              << "response:           " << response_total / n << " ms/step\n"
              << "whole step:         " << step_total / n << " ms/step\n"
              << "fail-safe steps:    " << failsafe_steps << '\n'
              << "intersecting steps: " << intersecting_steps << '\n'
              << "output:             " << out.string() << '\n'
              << "state hash:         " << hash << '\n';
  }
  if (intersecting_steps > 0) {
    throw std::runtime_error(std::to_string(intersecting_steps) + " step(s) ended with intersecting triangle pairs");
  }
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto* command = app.add_subcommand("simulate", "Run a cloth scene; write frames, stats.csv and pictures");
  command->footer("Exit code: 0 when every checked step ended free of intersections; 1 when a step ended with "
                  "intersecting triangle pairs (the summary and stats.csv are written first) or on any error.");
  auto options = std::make_shared<SimulateOptions>();
  command->add_option("--scene", options->scene, "box, character, walker, rabbit, cat, dinosaur, human, bird, sphere, "
                                                 "cube, fish, or file (with --obstacle)");
  command->add_option("--cloth", options->cloth, "The paper's cloth: A (20x20), B (30x30), C (50x50)")
      ->check(CLI::IsMember({"A", "B", "C"}));
  command->add_option("--resolution", options->resolution, "N x N cloth vertices instead of --cloth (the thickness must stay below half the edge length: "
                      "above about 200 with the default thickness, give a smaller --thickness)")
      ->check(CLI::Range(2, simulation::kMaxResolution));
  command->add_option("--steps", options->steps, "Number of steps (default: the scene's)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  command->add_option("--dt", options->dt, "Step in seconds (default 0.005)");
  add_filter_option(*command, options->filter, "--culling", {{"filters", "combined"}});
  add_network_option(*command, options->network, "--network-model");
  add_bvh_option(*command, options->bvh);
  command->add_option("--frames-every", options->frames_every, "Write a frame every K steps (default: 12 frames)");
  command->add_option("--check-every", options->check_every, "Run the intersection check every K steps (default 1)");
  command->add_option("--thickness", options->thickness, "Cloth thickness in metres");
  command->add_option("--friction", options->friction, "Coulomb friction coefficient");
  command->add_option("--contact-reach", options->contact_reach,
                      "Re-apply earlier steps' contacts before detection while their gap is within this many "
                      "thicknesses (default 4; 0 turns the contact memory off)");
  add_cache_option(*command, options->cache, "--model-dir");
  command->add_option("--obstacle", options->obstacle_file, "Obstacle mesh file for --scene file");
  command->add_option("--model", options->obstacle_file, "old spelling of --obstacle")->group("");
  command->add_flag("--no-pictures", options->no_pictures, "Skip PNG renders and the contact sheet");
  command->add_option("--out", options->out, "Output folder")->required();
  add_json_flag(*command, options->json);
  add_quiet_flag(*command, options->quiet);
  command->callback([options] { run(*options); });
}

}  // namespace clothcd::cli
