// `clothcd convert IN OUT`: read any mesh format assimp knows, write OBJ or ASCII PLY.
#include <iostream>
#include <string>

#include "clothcd/mesh/mesh_io.hpp"
#include "commands.hpp"

namespace clothcd::cli {

void add_convert_command(CLI::App& app) {
  auto* command = app.add_subcommand("convert", "Convert a mesh to OBJ or PLY (by the output extension)");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  command->add_option("IN", *in, "Input mesh file")->required();
  command->add_option("OUT", *out, "Output file, .obj or .ply")->required();
  command->callback([in, out] {
    LoadReport report;
    const TriangleMesh mesh = load_mesh(*in, {}, &report);
    save_mesh(mesh, *out);
    std::cout << "wrote " << *out << ": " << mesh.vertex_count() << " vertices, " << mesh.face_count() << " faces ("
              << report.degenerate_faces_dropped << " degenerate dropped)\n";
  });
}

}  // namespace clothcd::cli
