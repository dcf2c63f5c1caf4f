// `clothcd convert IN OUT`: read any mesh format assimp knows, write OBJ or ASCII PLY.
#include <iostream>
#include <string>

#include "clothcd/mesh/mesh_io.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct ConvertOptions {
  std::string in;
  std::string out;
  bool json = false;
};

void run_convert(const ConvertOptions& options) {
  check_output_file(options.out, "OUT", kMeshOutputExtensions);
  LoadReport report;
  const TriangleMesh mesh = load_mesh(options.in, {}, &report);
  save_mesh(mesh, options.out);
  if (options.json) {
    Json out = json_report("convert");
    out["in"] = options.in;
    out["out"] = options.out;
    out["vertices"] = mesh.vertex_count();
    out["faces"] = mesh.face_count();
    out["degenerate_faces_dropped"] = report.degenerate_faces_dropped;
    print_json(out);
    return;
  }
  std::cout << "wrote " << options.out << ": " << mesh.vertex_count() << " vertices, " << mesh.face_count()
            << " faces (" << report.degenerate_faces_dropped << " degenerate dropped)\n";
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto* command = app.add_subcommand("convert", "Convert a mesh to OBJ or PLY (by the output extension)");
  auto options = std::make_shared<ConvertOptions>();
  command->add_option("IN", options->in, "Input mesh file")->required();
  command->add_option("OUT", options->out, "Output file, .obj or .ply")->required();
  add_json_flag(*command, options->json);
  command->callback([options] { run_convert(*options); });
}

}  // namespace clothcd::cli
