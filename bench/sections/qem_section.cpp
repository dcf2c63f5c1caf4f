// Section "qem": the bunny (75k faces) simplified to 10% by clothcd's QEM, meshoptimizer's meshopt_simplify and CGAL's
// Garland-Heckbert edge collapse in the same run: time, time ratio and two-sided Hausdorff distance.
#include <meshoptimizer.h>

// CGAL's Garland-Heckbert policies trip GCC 12's -Wmaybe-uninitialized inside Eigen's fixed 4x4 matrices (a false
// positive in a system header's inlined code).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/charts.hpp"
#include "clothcd/geometry/hausdorff.hpp"
#include "clothcd/geometry/simple_bounds.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"

namespace clothcd::bench {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

// Drops vertices no face uses (so the Hausdorff sampling only sees the surface).
TriangleMesh compact(const Vertices& vertices, const std::vector<std::array<int, 3>>& faces) {
  std::vector<int> index(static_cast<std::size_t>(vertices.rows()), -1);
  TriangleMesh out;
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  int count = 0;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& i = index[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(k)])];
      if (i < 0) i = count++;
      out.faces(static_cast<Eigen::Index>(f), k) = i;
    }
  out.vertices.resize(count, 3);
  for (std::size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0) out.vertices.row(index[v]) = vertices.row(static_cast<Eigen::Index>(v));
  return out;
}

// meshoptimizer with an unbounded target error (1.0 of the extent) and no border lock: only the face count stops it.
TriangleMesh simplify_meshopt(const TriangleMesh& mesh, int target_faces) {
  std::vector<float> positions(mesh.vertices.size());
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      positions[static_cast<std::size_t>(3 * v + k)] = static_cast<float>(mesh.vertices(v, k));
  std::vector<unsigned> indices(static_cast<std::size_t>(mesh.faces.size()));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < 3; ++k) indices[static_cast<std::size_t>(3 * f + k)] = static_cast<unsigned>(mesh.faces(f, k));
  std::vector<unsigned> out(indices.size());
  float error = 0;
  const std::size_t count =
      meshopt_simplify(out.data(), indices.data(), indices.size(), positions.data(),
                       static_cast<std::size_t>(mesh.vertex_count()), 3 * sizeof(float),
                       static_cast<std::size_t>(target_faces) * 3, 1.0f, 0, &error);
  std::vector<std::array<int, 3>> faces(count / 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    faces[f] = {static_cast<int>(out[3 * f]), static_cast<int>(out[3 * f + 1]), static_cast<int>(out[3 * f + 2])};
  return compact(mesh.vertices, faces);
}

CgalMesh to_cgal(const TriangleMesh& mesh) {
  CgalMesh out;
  std::vector<CgalMesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    v.push_back(out.add_vertex({mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2)}));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    out.add_face(v[static_cast<std::size_t>(mesh.faces(f, 0))], v[static_cast<std::size_t>(mesh.faces(f, 1))],
                 v[static_cast<std::size_t>(mesh.faces(f, 2))]);
  return out;
}

TriangleMesh from_cgal(CgalMesh& mesh) {
  mesh.collect_garbage();
  Vertices vertices(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    vertices.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  std::vector<std::array<int, 3>> faces;
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    std::size_t k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[std::min<std::size_t>(k++, 2)] = int(v.idx());
    faces.push_back(t);
  }
  return compact(vertices, faces);
}

// CGAL's edge collapse with the Garland-Heckbert plane quadrics, stopped at 3F/2 edges (those of a closed mesh).
TriangleMesh simplify_cgal(const TriangleMesh& mesh, int target_faces) {
  namespace SMS = CGAL::Surface_mesh_simplification;
  CgalMesh cgal = to_cgal(mesh);
  SMS::Count_stop_predicate<CgalMesh> stop(static_cast<std::size_t>(target_faces) * 3 / 2);
  SMS::GarlandHeckbert_plane_policies<CgalMesh, Kernel> policies(cgal);
  SMS::edge_collapse(cgal, stop,
                     CGAL::parameters::get_cost(policies.get_cost()).get_placement(policies.get_placement()));
  return from_cgal(cgal);
}

// The middle value (the upper one of the two middle values for an even count). `values` must not be empty.
double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
  return values[values.size() / 2];
}

struct Result {
  std::string library;
  TriangleMesh mesh;
  double ms = 0;
  double max_pct = 0, mean_pct = 0;
  std::string reference;  // the same library, measured earlier on a reference machine
};

SectionReport run_qem(const BenchContext& context) {
  context.progress("1/4 loading the bunny (catalog model rabbit)");
  const TriangleMesh rabbit = load_mesh(fetch_model("rabbit", context.obstacle_model_dir));
  const int target = static_cast<int>(rabbit.face_count() / 10);
  // Ours and meshoptimizer alternate run by run, so load from other processes on a shared machine hits both alike.
  const int runs = context.quick ? 1 : 11;
  geometry::SimplifySettings settings;
  settings.target_faces = target;
  std::vector<Result> results(3);
  results[0].library = "clothcd `simplify_qem`";
  results[1].library = "meshoptimizer `meshopt_simplify`";
  results[2].library = "CGAL Garland-Heckbert `edge_collapse`";
  results[1].reference = "30 ms, 0.17 / 0.023";
  results[2].reference = "751 ms, 0.12 / 0.015";
  context.progress("2/4 clothcd QEM and meshoptimizer, " + std::to_string(runs) + " alternating runs each");
  std::vector<double> ours_times, meshopt_times;
  for (int run = 0; run < runs; ++run) {
    ours_times.push_back(time_ms([&] { results[0].mesh = geometry::simplify_qem(rabbit, settings).mesh; }));
    meshopt_times.push_back(time_ms([&] { results[1].mesh = simplify_meshopt(rabbit, target); }));
  }
  results[0].ms = median(ours_times);
  results[1].ms = median(meshopt_times);
  context.progress("3/4 CGAL");
  results[2].ms = median_ms(context.quick ? 1 : 3, [&] { results[2].mesh = simplify_cgal(rabbit, target); });
  context.progress("4/4 two-sided Hausdorff distances");
  const geometry::Aabb box = geometry::compute_aabb(rabbit.vertices);
  const double diagonal = (box.max - box.min).norm();
  geometry::HausdorffSettings hausdorff;
  hausdorff.samples = context.quick ? 50000 : 500000;
  for (Result& r : results) {
    const geometry::HausdorffResult h = geometry::measure_hausdorff(rabbit, r.mesh, hausdorff);
    r.max_pct = 100 * h.max / diagonal;
    r.mean_pct = 100 * h.mean / diagonal;
  }

  CsvFile csv(context.out_dir / "qem.csv",
              "mesh,faces_in,library,faces_out,time_ms,time_ratio_to_meshopt,hausdorff_max_pct_diag,"
              "hausdorff_mean_pct_diag");
  std::vector<std::vector<std::string>> rows;
  BarChart chart;
  chart.text = {"QEM simplification of the bunny to 10% of its faces", "library",
                "time / meshoptimizer's time (ratio)", ""};
  chart.series = {"time ratio"};
  const double meshopt_ms = results[1].ms;
  for (const Result& r : results) {
    csv.row({"rabbit", std::to_string(rabbit.face_count()), csv_text(r.library), std::to_string(r.mesh.face_count()),
             number(r.ms, 6), number(r.ms / meshopt_ms, 4), number(r.max_pct, 4), number(r.mean_pct, 4)});
    rows.push_back({r.library, std::to_string(r.mesh.face_count()), number(r.ms, 4), number(r.ms / meshopt_ms, 3),
                    number(r.max_pct, 3), number(r.mean_pct, 3), r.reference.empty() ? "-" : r.reference});
    chart.categories.push_back(r.library);
    chart.values.push_back({r.ms / meshopt_ms});
  }
  write_bar_chart_svg((context.out_dir / "qem_time.svg").string(), chart);

  const Result& ours = results[0];
  const bool quality = ours.max_pct <= results[1].max_pct && ours.max_pct <= results[2].max_pct;
  const double speed = ours.ms / meshopt_ms;
  std::string md = "## QEM simplification: bunny to 10% against meshoptimizer and CGAL\n\n";
  md += "The bunny (catalog model `rabbit`, " + std::to_string(rabbit.face_count()) + " faces) simplified to " +
        std::to_string(target) + " faces. Time: median of " + std::to_string(runs) +
        " runs, clothcd and meshoptimizer alternating (CGAL: " + std::to_string(context.quick ? 1 : 3) +
        " runs), one thread. Hausdorff: two-sided, every vertex, every face centroid and " +
        std::to_string(hausdorff.samples) +
        " area-weighted samples per side, exact point-triangle distance, in % of the input's bounding-box diagonal. "
        "The paper gives no QEM figures; the last column is the same library on the reference machine "
        "(the project's reference figures, measured earlier on a 2-core machine of this kind: time, max / mean "
        "Hausdorff %).\n\n";
  md += markdown_table({"library", "faces", "time ms", "x meshopt", "max Hausdorff %", "mean Hausdorff %",
                        "reference machine"},
                       rows);
  md += "\nQuality (max Hausdorff no larger than both peers'): " + std::string(quality ? "**met**" : "**missed**") +
        ". Speed (within 2x of meshoptimizer): " + (speed <= 2.0 ? "**met**" : "**missed**") + " (" +
        number(speed, 3) + "x).\n\n";
  md += "![QEM time relative to meshoptimizer](qem_time.svg)\n";
  return {md, {"qem.csv", "qem_time.svg"}};
}

const SectionRegistrar registrar{
    {10, "qem", "QEM simplification of the bunny to 10%: clothcd vs meshoptimizer vs CGAL (time, Hausdorff)", run_qem}};

}  // namespace
}  // namespace clothcd::bench
