// `clothcd info MESH`: counts, bounding box, components, watertightness and degenerate faces of a mesh file.
#include <iostream>
#include <string>

#include "clothcd/mesh/mesh_info.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "commands.hpp"

namespace clothcd::cli {

void add_info_command(CLI::App& app) {
  auto* command = app.add_subcommand("info", "Print vertices, faces, bounding box, components and watertightness");
  auto path = std::make_shared<std::string>();
  command->add_option("MESH", *path, "Mesh file (any format assimp reads)")->required();
  command->callback([path] {
    LoadOptions options;
    options.drop_degenerate_faces = false;  // count them instead
    LoadReport report;
    const TriangleMesh mesh = load_mesh(*path, options, &report);
    const MeshInfo info = compute_mesh_info(mesh);
    std::cout << "file:             " << *path << '\n'
              << "vertices:         " << info.vertices << "  (" << report.vertices_joined << " identical joined)\n"
              << "faces:            " << info.faces << '\n'
              << "bounding box:     [" << info.bbox_min.transpose() << "] .. [" << info.bbox_max.transpose() << "]\n"
              << "components:       " << info.components << '\n'
              << "watertight:       " << (info.watertight ? "yes" : "no") << "  (" << info.boundary_edges
              << " boundary edges, " << info.non_manifold_edges << " non-manifold edges)\n"
              << "degenerate faces: " << info.degenerate_faces << '\n'
              << "surface area:     " << info.surface_area << '\n';
  });
}

}  // namespace clothcd::cli
