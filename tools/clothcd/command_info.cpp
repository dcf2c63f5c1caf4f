// `clothcd info MESH`: counts, bounding box, components, watertightness and degenerate faces of a mesh file.
#include <iostream>
#include <string>

#include "clothcd/mesh/mesh_info.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "commands.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
};

void run_info(const InfoOptions& options) {
  LoadOptions load;
  load.drop_degenerate_faces = false;  // count them instead
  LoadReport report;
  const TriangleMesh mesh = load_mesh(options.path, load, &report);
  const MeshInfo info = compute_mesh_info(mesh);
  if (options.json) {
    Json out = json_report("info");
    out["file"] = options.path;
    out["vertices"] = info.vertices;
    out["vertices_joined"] = report.vertices_joined;
    out["faces"] = info.faces;
    out["bbox_min"] = json_vector(info.bbox_min);
    out["bbox_max"] = json_vector(info.bbox_max);
    out["components"] = info.components;
    out["watertight"] = info.watertight;
    out["boundary_edges"] = info.boundary_edges;
    out["non_manifold_edges"] = info.non_manifold_edges;
    out["degenerate_faces"] = info.degenerate_faces;
    out["surface_area"] = info.surface_area;
    print_json(out);
    return;
  }
  std::cout << "file:             " << options.path << '\n'
            << "vertices:         " << info.vertices << "  (" << report.vertices_joined << " identical joined)\n"
            << "faces:            " << info.faces << '\n'
            << "bounding box:     [" << info.bbox_min.transpose() << "] .. [" << info.bbox_max.transpose() << "]\n"
            << "components:       " << info.components << '\n'
            << "watertight:       " << (info.watertight ? "yes" : "no") << "  (" << info.boundary_edges
            << " boundary edges, " << info.non_manifold_edges << " non-manifold edges)\n"
            << "degenerate faces: " << info.degenerate_faces << '\n'
            << "surface area:     " << info.surface_area << '\n';
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto* command = app.add_subcommand("info", "Print vertices, faces, bounding box, components and watertightness");
  auto options = std::make_shared<InfoOptions>();
  command->add_option("MESH", options->path, "Mesh file (any format assimp reads)")->required();
  add_json_flag(*command, options->json);
  command->callback([options] { run_info(*options); });
}

}  // namespace clothcd::cli
