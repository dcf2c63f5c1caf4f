// `clothcd simplify IN OUT (--ratio R | --faces N) [--non-edge-threshold D] [--max-error E] [--hausdorff] [--json]`: QEM
// simplification (Garland & Heckbert) of a mesh file, with timing and optionally the Hausdorff distance to the input.
#include <chrono>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "clothcd/geometry/hausdorff.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {

void add_simplify_command(CLI::App& app) {
  auto* command = app.add_subcommand("simplify", "Simplify a mesh by quadric error metrics (QEM)");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto settings = std::make_shared<geometry::SimplifySettings>();
  auto hausdorff = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  command->add_option("IN", *in, "Input mesh file")->required();
  command->add_option("OUT", *out, "Output file, .obj or .ply")->required();
  auto* ratio = command->add_option("--ratio", settings->target_ratio,
                                    "Fraction of the faces to keep, in (0, 1] (0.1 = the paper's 90% simplified)")
                    ->check(finite_number(0.0, 1.0, true));
  auto* faces = command->add_option("--faces", settings->target_faces, "Number of faces to keep (at least 1)")
                    ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  auto* error = command->add_option("--max-error", settings->max_error,
                                    "Never contract a pair whose error exceeds this distance (model units)")
                    ->check(finite_number(0.0, HUGE_VAL));
  ratio->excludes(faces);
  command->add_option("--non-edge-threshold", settings->non_edge_threshold,
                      "Also contract vertices closer than this distance that share no edge (model units)")
      ->check(finite_number(0.0, HUGE_VAL));
  command->add_flag("--hausdorff", *hausdorff, "Print the two-sided sampled Hausdorff distance to the input");
  add_json_flag(*command, *json);
  command->callback([=] {
    if (ratio->count() + faces->count() + error->count() == 0)
      throw std::invalid_argument("simplify: give --ratio R or --faces N (or --max-error E)");
    check_output_file(*out, "OUT", kMeshOutputExtensions);
    LoadReport report_of_input;
    const TriangleMesh mesh = load_mesh(*in, {}, &report_of_input);
    const auto start = std::chrono::steady_clock::now();
    const geometry::SimplifyResult result = geometry::simplify_qem(mesh, *settings);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    save_mesh(result.mesh, *out);
    const double diagonal = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
    std::optional<geometry::HausdorffResult> h;
    if (*hausdorff) h = geometry::measure_hausdorff(mesh, result.mesh);
    if (*json) {
      Json report = json_report("simplify");
      report["in"] = *in;
      report["out"] = *out;
      report["faces_before"] = result.faces_before;
      report["faces_after"] = result.faces_after;
      report["reached_target"] = result.reached_target;
      report["vertices_before"] = mesh.vertex_count();
      report["vertices_after"] = result.mesh.vertex_count();
      report["degenerate_faces_dropped"] = report_of_input.degenerate_faces_dropped;
      report["time_ms"] = ms;
      report["max_error"] = result.max_error;
      if (h) report["hausdorff"] = {{"max", h->max}, {"mean", h->mean}, {"bbox_diagonal", diagonal}};
      print_json(report);
      return;
    }
    std::cout << "faces:        " << result.faces_before << " -> " << result.faces_after
              << (result.reached_target ? "" : "  (target not reached: no valid contraction left)") << '\n';
    if (report_of_input.degenerate_faces_dropped > 0)
      std::cout << "dropped:      " << report_of_input.degenerate_faces_dropped << " zero-area faces of the input file\n";
    std::cout << "vertices:     " << mesh.vertex_count() << " -> " << result.mesh.vertex_count() << '\n'
              << "time:         " << ms << " ms\n"
              << "max error:    " << result.max_error << " (largest contraction error, model units)\n";
    if (h)
      std::cout << "hausdorff:    max " << h->max << " (" << 100.0 * h->max / diagonal << "% of bbox diagonal), mean "
                << h->mean << " (" << 100.0 * h->mean / diagonal << "%)\n";
    std::cout << "wrote " << *out << '\n';
  });
}

}  // namespace clothcd::cli
