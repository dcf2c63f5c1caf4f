// Meshes, simplification, bounding boxes, generators and pictures for Python.
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/mesh_validation.hpp"
#include "clothcd/render/image.hpp"
#include "clothcd/render/rasterizer.hpp"

namespace clothcd::python {
namespace {

using MeshArrays = std::tuple<nb::ndarray<nb::numpy, double>, nb::ndarray<nb::numpy, int>>;

MeshArrays to_arrays(const TriangleMesh& mesh) { return {matrix_to_numpy(mesh.vertices), matrix_to_numpy(mesh.faces)}; }

geometry::ObbMethod obb_method(const std::string& name) {
  if (name == "covariance") return geometry::ObbMethod::Covariance;
  if (name == "adaptive") return geometry::ObbMethod::FastAdaptive;
  if (name == "adaptive-simplified") return geometry::ObbMethod::FastAdaptiveSimplified;
  if (name == "tight") return geometry::ObbMethod::Tight;
  throw std::invalid_argument("obb: unknown method '" + name + "' (covariance, adaptive, adaptive-simplified, tight)");
}

}  // namespace

void bind_mesh(nb::module_& m) {
  m.def(
      "load_mesh", [](const std::string& path) { return to_arrays(load_mesh(path)); }, nb::arg("path"),
      "Reads a mesh file (any format assimp reads) as (vertices (N, 3) float64, faces (F, 3) int32); raises OSError "
      "naming the file when it is missing, truncated or invalid.");
  m.def(
      "load_mesh_frames",
      [](const std::string& start, const std::string& end) {
        MeshFrames frames = load_mesh_frames(start, end);
        return std::make_tuple(matrix_to_numpy(frames.start.vertices), matrix_to_numpy(frames.end),
                               matrix_to_numpy(frames.start.faces));
      },
      nb::arg("start"), nb::arg("end"),
      "Reads two frames of one mesh with one numbering (as `clothcd detect` does): (x0, x1, faces).");
  m.def(
      "save_mesh",
      [](const std::string& path, const DoubleArray& vertices, const IntArray& faces) {
        save_mesh(TriangleMesh{to_vertices(vertices, "vertices"), to_faces(faces, "faces")}, path);
      },
      nb::arg("path"), nb::arg("vertices"), nb::arg("faces"), "Writes OBJ or ASCII PLY (by extension), full precision.");
  m.def(
      "simplify",
      [](const DoubleArray& vertices, const IntArray& faces, double ratio, int target_faces, double non_edge_threshold) {
        geometry::SimplifySettings settings;
        settings.target_ratio = ratio;
        settings.target_faces = target_faces;
        settings.non_edge_threshold = non_edge_threshold;
        TriangleMesh mesh{to_vertices(vertices, "vertices"), to_faces(faces, "faces")};
        return to_arrays(geometry::simplify_qem(mesh, settings).mesh);
      },
      nb::arg("vertices"), nb::arg("faces"), nb::kw_only(), nb::arg("ratio") = -1.0, nb::arg("faces_target") = -1,
      nb::arg("non_edge_threshold") = 0.0,
      "Garland-Heckbert QEM simplification to `ratio` of the faces or to `faces_target` faces; returns (vertices, "
      "faces).");
  m.def(
      "obb",
      [](const DoubleArray& vertices, const IntArray& faces, const std::string& method) {
        TriangleMesh mesh{to_vertices(vertices, "vertices"), to_faces(faces, "faces")};
        const geometry::Obb box = geometry::compute_obb(mesh, obb_method(method));
        std::vector<double> axes(9);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) axes[static_cast<std::size_t>(3 * i + j)] = box.axes(i, j);
        return std::make_tuple(to_numpy(std::vector<double>(box.center.data(), box.center.data() + 3), {3}),
                               to_numpy(std::move(axes), {3, 3}),
                               to_numpy(std::vector<double>(box.half_extents.data(), box.half_extents.data() + 3), {3}));
      },
      nb::arg("vertices"), nb::arg("faces"), nb::arg("method") = "adaptive",
      "Oriented bounding box: (center (3,), axes (3, 3) with the axes as columns, half_extents (3,)).");
  m.def("make_paper_cloth", [](char name, double size) { return to_arrays(make_paper_cloth(name, size)); },
        nb::arg("name"), nb::arg("size") = 1.0, "The paper's cloth 'A', 'B' or 'C' (a square grid in the xz plane).");
  m.def("make_grid", [](int columns, int rows, double width, double depth) {
        return to_arrays(make_grid(columns, rows, width, depth)); },
        nb::arg("columns"), nb::arg("rows"), nb::arg("width") = 1.0, nb::arg("depth") = 1.0,
        "A grid of columns x rows vertices in the xz plane.");
  m.def("make_uv_sphere", [](double radius, int slices, int stacks) {
        return to_arrays(make_uv_sphere(radius, slices, stacks)); },
        nb::arg("radius") = 1.0, nb::arg("slices") = 32, nb::arg("stacks") = 16, "A UV sphere about the origin.");
  m.def(
      "render_png",
      [](const std::string& path, const std::vector<std::tuple<DoubleArray, IntArray, std::tuple<double, double, double>>>& items,
         int width, int height) {
        std::vector<TriangleMesh> meshes;
        meshes.reserve(items.size());
        std::vector<render::RenderItem> draw;
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
        for (const auto& [vertices, faces, color] : items) {
          meshes.push_back({to_vertices(vertices, "vertices"), to_faces(faces, "faces")});
          validate_mesh(meshes.back(), "render_png");
          lo = lo.cwiseMin(meshes.back().vertices.colwise().minCoeff().transpose());
          hi = hi.cwiseMax(meshes.back().vertices.colwise().maxCoeff().transpose());
          draw.push_back({&meshes.back(), {std::get<0>(color), std::get<1>(color), std::get<2>(color)}});
        }
        if (draw.empty()) throw std::invalid_argument("render_png: no mesh to draw");
        render::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        render::write_png(render::render(draw, render::frame_box(lo, hi), settings), path);
      },
      nb::arg("path"), nb::arg("meshes"), nb::arg("width") = 640, nb::arg("height") = 480,
      "Draws meshes [(vertices, faces, (r, g, b)), ...] (colours in [0, 1]) framed from the front and writes a PNG.");
}

}  // namespace clothcd::python
