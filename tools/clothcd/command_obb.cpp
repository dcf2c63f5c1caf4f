// `clothcd obb MESH [--method aabb|sphere|covariance|adaptive|adaptive-simplified|tight] [--simplify R] [--json]`:
// a bounding volume of a mesh file (or catalog model name) with its volume, compactness tau and construction time.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/geometry/simple_bounds.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "commands.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(10) << v.x() << ' ' << v.y() << ' ' << v.z();
  return out.str();
}

// A mesh file, or a model of the catalog (fetched into the cache folder) when no such file exists.
TriangleMesh load_file_or_model(const std::string& name, const std::string& cache, LoadReport& report) {
  if (std::filesystem::exists(name)) return load_mesh(name, {}, &report);
  for (const ModelSource& model : model_catalog()) {
    if (model.name == name) return load_mesh(fetch_model(name, cache), {}, &report);
  }
  return load_mesh(name, {}, &report);  // reports the missing file
}

}  // namespace

void add_obb_command(CLI::App& app) {
  auto* command = app.add_subcommand("obb", "Bounding volume of a mesh: centre, axes, extents, volume, tau, time");
  auto path = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>("adaptive-simplified");
  auto settings = std::make_shared<geometry::ObbSettings>();
  auto json = std::make_shared<bool>(false);
  auto cache = std::make_shared<std::string>();
  command->add_option("MESH", *path, "Mesh file, or a model name of `clothcd meshes` (e.g. rabbit)")->required();
  command->add_option("--method", *method, "aabb, sphere, covariance, adaptive, adaptive-simplified or tight")
      ->check(CLI::IsMember({"aabb", "sphere", "covariance", "adaptive", "adaptive-simplified", "tight"}))
      ->capture_default_str();
  command->add_option("--simplify", settings->simplify_ratio,
                      "adaptive-simplified: fraction of the faces the simplified model keeps")
      ->check(finite_number(0.0, 1.0, true))
      ->capture_default_str();
  command->add_option("--slabs", settings->slabs, "adaptive methods: slabs per axis")->check(CLI::Range(1, 256));
  add_cache_option(*command, *cache);
  add_json_flag(*command, *json);
  command->callback([=] {
    LoadReport report_of_input;
    const TriangleMesh mesh = load_file_or_model(*path, *cache, report_of_input);
    const std::map<std::string, geometry::ObbMethod> methods = {
        {"covariance", geometry::ObbMethod::Covariance},
        {"adaptive", geometry::ObbMethod::FastAdaptive},
        {"adaptive-simplified", geometry::ObbMethod::FastAdaptiveSimplified},
        {"tight", geometry::ObbMethod::Tight}};
    geometry::Obb box;
    double radius = -1.0;
    const auto start = std::chrono::steady_clock::now();
    if (*method == "aabb") {
      const geometry::Aabb aabb = geometry::compute_aabb(mesh.vertices);
      box.center = 0.5 * (aabb.min + aabb.max);
      box.half_extents = 0.5 * (aabb.max - aabb.min);
    } else if (*method == "sphere") {
      const geometry::Sphere sphere = geometry::compute_bounding_sphere(mesh.vertices);
      box.center = sphere.center;
      radius = sphere.radius;
    } else {
      box = geometry::compute_obb(mesh, methods.at(*method), *settings);
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double volume = radius >= 0 ? 4.0 / 3.0 * M_PI * radius * radius * radius : box.volume();
    const double model_volume = geometry::mesh_volume(mesh);
    const double tau = model_volume > 0 ? volume / model_volume : std::nan("");
    if (*json) {
      Json report = json_report("obb");
      report["mesh"] = *path;
      report["method"] = *method;
      report["center"] = json_vector(box.center);
      if (radius >= 0) {
        report["radius"] = radius;
      } else {
        report["axes"] = {json_vector(box.axes.col(0)), json_vector(box.axes.col(1)), json_vector(box.axes.col(2))};
        report["half_extents"] = json_vector(box.half_extents);
      }
      report["volume"] = volume;
      report["model_volume"] = model_volume;
      report["tau"] = tau;  // NaN (open mesh) is written as null
      report["time_ms"] = ms;
      report["degenerate_faces_dropped"] = report_of_input.degenerate_faces_dropped;
      print_json(report);
      return;
    }
    std::ostringstream out;
    out << std::setprecision(10) << "method:       " << *method << "\ncenter:       " << vector_text(box.center) << '\n';
    if (radius >= 0) {
      out << "radius:       " << radius << '\n';
    } else {
      for (int a = 0; a < 3; ++a) out << "axis " << a << ":       " << vector_text(box.axes.col(a)) << '\n';
      out << "half extents: " << vector_text(box.half_extents) << '\n';
    }
    out << "volume:       " << volume << "\nmodel volume: " << model_volume
        << (model_volume > 0 ? "" : "  (open or inside-out mesh: tau undefined)") << "\ntau:          " << tau
        << "\ntime:         " << ms << " ms\n";
    if (report_of_input.degenerate_faces_dropped > 0)
      out << "dropped:      " << report_of_input.degenerate_faces_dropped << " zero-area faces of the input file\n";
    std::cout << out.str();
  });
}

}  // namespace clothcd::cli
