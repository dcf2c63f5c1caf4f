// Geometry benchmark: (1) QEM simplification of the bunny to 10% against meshoptimizer's meshopt_simplify and CGAL's
// Garland-Heckbert edge collapse (time and two-sided sampled Hausdorff distance); (2) Jin et al. Table 1 / Figure 11:
// construction time of the OBB methods (a) covariance, (b) fast adaptive, (c) fast adaptive on the simplified model
// (per update, simplification counted once) and the volume ratio of each box to the tight reference (ours and CGAL's
// optimal box). Peers are measured in the same run; results go to CSV files.
// Usage: clothcd_bench_geometry [--models DIR] [--out DIR] [--quick]
#include <meshoptimizer.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/optimal_bounding_box.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <tuple>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "clothcd/geometry/convex_hull.hpp"
#include "clothcd/geometry/hausdorff.hpp"
#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/geometry/simple_bounds.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"

namespace {

using namespace clothcd;
using namespace clothcd::geometry;
using Clock = std::chrono::steady_clock;
using Kernel = CGAL::Simple_cartesian<double>;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

// Median wall time of `runs` calls, in milliseconds.
double median_ms(int runs, const std::function<void()>& work) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    work();
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

// Drops vertices no face uses (so Hausdorff sampling only sees the surface).
TriangleMesh compact(const Vertices& vertices, const std::vector<std::array<int, 3>>& faces) {
  std::vector<int> index(static_cast<size_t>(vertices.rows()), -1);
  TriangleMesh out;
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  int count = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& i = index[size_t(faces[f][size_t(k)])];
      if (i < 0) i = count++;
      out.faces(Eigen::Index(f), k) = i;
    }
  out.vertices.resize(count, 3);
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0) out.vertices.row(index[v]) = vertices.row(Eigen::Index(v));
  return out;
}

TriangleMesh simplify_meshopt(const TriangleMesh& mesh, int target_faces) {
  std::vector<float> positions(mesh.vertices.data(), mesh.vertices.data() + mesh.vertices.size());
  std::vector<unsigned> indices(mesh.faces.data(), mesh.faces.data() + mesh.faces.size());
  std::vector<unsigned> out(indices.size());
  float error = 0;
  const size_t count = meshopt_simplify(out.data(), indices.data(), indices.size(), positions.data(),
                                        size_t(mesh.vertex_count()), 3 * sizeof(float), size_t(target_faces) * 3, 1.0f,
                                        0, &error);
  std::vector<std::array<int, 3>> faces(count / 3);
  for (size_t f = 0; f < faces.size(); ++f) faces[f] = {int(out[3 * f]), int(out[3 * f + 1]), int(out[3 * f + 2])};
  return compact(mesh.vertices, faces);
}

CgalMesh to_cgal(const TriangleMesh& mesh) {
  CgalMesh out;
  std::vector<CgalMesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    v.push_back(out.add_vertex({mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2)}));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    out.add_face(v[size_t(mesh.faces(f, 0))], v[size_t(mesh.faces(f, 1))], v[size_t(mesh.faces(f, 2))]);
  return out;
}

TriangleMesh from_cgal(CgalMesh& mesh) {
  mesh.collect_garbage();
  Vertices vertices(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    vertices.row(Eigen::Index(v.idx())) << p.x(), p.y(), p.z();
  }
  std::vector<std::array<int, 3>> faces;
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[size_t(std::min(k++, 2))] = int(v.idx());
    faces.push_back(t);
  }
  return compact(vertices, faces);
}

TriangleMesh simplify_cgal(const TriangleMesh& mesh, int target_faces) {
  namespace SMS = CGAL::Surface_mesh_simplification;
  CgalMesh cgal = to_cgal(mesh);
  SMS::Count_stop_predicate<CgalMesh> stop(size_t(target_faces) * 3 / 2);  // edges of a closed mesh: 3F/2
  SMS::GarlandHeckbert_plane_policies<CgalMesh, Kernel> policies(cgal);
  SMS::edge_collapse(cgal, stop, CGAL::parameters::get_cost(policies.get_cost()).get_placement(policies.get_placement()));
  return from_cgal(cgal);
}

double cgal_optimal_box_volume(const TriangleMesh& mesh) {
  std::vector<Kernel::Point_3> points;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    points.emplace_back(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  std::array<Kernel::Point_3, 8> corners;
  CGAL::oriented_bounding_box(points, corners, CGAL::parameters::use_convex_hull(true));
  TriangleMesh box;
  box.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) box.vertices.row(i) << corners[size_t(i)].x(), corners[size_t(i)].y(), corners[size_t(i)].z();
  const ConvexHull hull = compute_convex_hull(box.vertices);
  box.faces = hull.faces;
  return mesh_volume(box);
}

double diagonal(const TriangleMesh& mesh) {
  const Aabb box = compute_aabb(mesh.vertices);
  return (box.max - box.min).norm();
}

void bench_qem(const std::filesystem::path& models, const std::filesystem::path& out, bool quick) {
  const TriangleMesh rabbit = load_mesh(fetch_model("rabbit", models));
  const int target = static_cast<int>(rabbit.face_count() / 10);
  const int runs = quick ? 1 : 5;
  SimplifySettings settings;
  settings.target_faces = target;
  TriangleMesh ours, meshopt, cgal;
  const double t_ours = median_ms(runs, [&] { ours = simplify_qem(rabbit, settings).mesh; });
  const double t_meshopt = median_ms(runs, [&] { meshopt = simplify_meshopt(rabbit, target); });
  const double t_cgal = median_ms(quick ? 1 : 3, [&] { cgal = simplify_cgal(rabbit, target); });
  const double d = diagonal(rabbit);
  HausdorffSettings h;
  h.samples = quick ? 50000 : 500000;
  std::ofstream csv(out / "geometry_qem.csv");
  csv << "mesh,faces_in,library,faces_out,time_ms,time_ratio_to_meshopt,hausdorff_max_pct_diag,hausdorff_mean_pct_diag\n";
  std::printf("QEM: rabbit %lld -> %d faces (Hausdorff two-sided, %d samples per side + vertices + centroids)\n",
              static_cast<long long>(rabbit.face_count()), target, h.samples);
  std::printf("%-14s %8s %10s %8s %10s %10s\n", "library", "faces", "time ms", "x meshopt", "max %diag", "mean %diag");
  for (const auto& [name, mesh, t] : {std::tuple<const char*, TriangleMesh*, double>{"clothcd", &ours, t_ours},
                                      {"meshoptimizer", &meshopt, t_meshopt},
                                      {"cgal-gh", &cgal, t_cgal}}) {
    const HausdorffResult r = measure_hausdorff(rabbit, *mesh, h);
    std::printf("%-14s %8lld %10.1f %8.2f %10.4f %10.4f\n", name, static_cast<long long>(mesh->face_count()), t,
                t / t_meshopt, 100 * r.max / d, 100 * r.mean / d);
    csv << "rabbit," << rabbit.face_count() << ',' << name << ',' << mesh->face_count() << ',' << t << ','
        << t / t_meshopt << ',' << 100 * r.max / d << ',' << 100 * r.mean / d << '\n';
  }
}

// Figure 11 as a bar chart: per model (groups left to right: rabbit, cat, dinosaur, human) one bar per method, height
// = volume / tight volume on a 1.0 .. 1.4 scale (grey lines every 0.1); bars above 1.4 are clipped.
void write_chart(const std::filesystem::path& path, const std::vector<std::vector<double>>& ratios) {
  constexpr int kWidth = 640, kHeight = 320, kMargin = 20;
  constexpr unsigned char kColors[][3] = {{120, 120, 120}, {230, 159, 0}, {86, 180, 233}, {0, 158, 115}, {204, 121, 167}};
  std::vector<unsigned char> image(size_t(kWidth) * kHeight * 3, 255);
  auto fill = [&](int x0, int y0, int x1, int y1, const unsigned char* c) {
    for (int y = std::max(0, y0); y < std::min(kHeight, y1); ++y)
      for (int x = std::max(0, x0); x < std::min(kWidth, x1); ++x)
        for (int k = 0; k < 3; ++k) image[(size_t(y) * kWidth + size_t(x)) * 3 + size_t(k)] = c[k];
  };
  const unsigned char grey[3] = {210, 210, 210};
  auto y_of = [&](double ratio) {
    return kHeight - kMargin - int((std::min(ratio, 1.4) - 1.0) / 0.4 * (kHeight - 2 * kMargin));
  };
  for (double r = 1.0; r <= 1.401; r += 0.1) fill(kMargin, y_of(r), kWidth - kMargin, y_of(r) + 1, grey);
  const int group = (kWidth - 2 * kMargin) / int(std::max<size_t>(1, ratios.size()));
  for (size_t m = 0; m < ratios.size(); ++m) {
    const int bar = (group - 20) / int(std::max<size_t>(1, ratios[m].size()));
    for (size_t b = 0; b < ratios[m].size(); ++b) {
      const int x = kMargin + int(m) * group + 10 + int(b) * bar;
      fill(x, y_of(ratios[m][b]), x + bar - 2, kHeight - kMargin, kColors[b % 5]);
    }
  }
  stbi_write_png(path.string().c_str(), kWidth, kHeight, 3, image.data(), kWidth * 3);
}

void bench_obb(const std::filesystem::path& models, const std::filesystem::path& out, bool quick) {
  std::vector<std::vector<double>> chart;
  std::ofstream csv(out / "geometry_obb.csv");
  csv << "model,faces,method,time_ms,once_ms,volume,tau,ratio_to_tight,ratio_to_cgal_optimal\n";
  std::printf("\nOBB (Jin et al. Table 1 / Fig. 11): time per build, volume ratio to our tight box and to CGAL's\n");
  std::printf("%-9s %-26s %10s %10s %8s %8s %8s\n", "model", "method", "time ms", "once ms", "tau", "/tight", "/cgal");
  for (const char* name : {"rabbit", "cat", "dinosaur", "human"}) {
    const TriangleMesh mesh = load_mesh(fetch_model(name, models));
    const double model_volume = std::abs(mesh_volume(mesh));
    const int runs = quick ? 3 : 31;
    Obb tight;
    const double t_tight = median_ms(quick ? 1 : 3, [&] { tight = compute_obb(mesh, ObbMethod::Tight); });
    double cgal_volume = 0;
    const double t_cgal = median_ms(1, [&] { cgal_volume = cgal_optimal_box_volume(mesh); });
    struct Row {
      std::string method;
      double time, once, volume;
    };
    std::vector<Row> rows;
    Aabb aabb;
    rows.push_back({"aabb", median_ms(runs, [&] { aabb = compute_aabb(mesh.vertices); }), 0, aabb.volume()});
    Sphere sphere;
    rows.push_back({"sphere (Welzl)", median_ms(runs, [&] { sphere = compute_bounding_sphere(mesh.vertices); }), 0,
                    4.0 / 3.0 * M_PI * std::pow(sphere.radius, 3)});
    Obb box;
    rows.push_back({"(a) covariance", median_ms(runs, [&] { box = compute_obb(mesh, ObbMethod::Covariance); }), 0,
                    box.volume()});
    ObbSettings paper;
    paper.refine_axes = false;
    rows.push_back({"(b) adaptive, eqs. 11-18",
                    median_ms(runs, [&] { box = compute_obb(mesh, ObbMethod::FastAdaptive, paper); }), 0, box.volume()});
    rows.push_back({"(b) adaptive + refine", median_ms(runs, [&] { box = compute_obb(mesh, ObbMethod::FastAdaptive); }),
                    0, box.volume()});
    for (const auto& [label, settings] : {std::pair<const char*, ObbSettings>{"(c) simplified, eqs. 11-18", paper},
                                          {"(c) simplified + refine", ObbSettings{}}}) {
      std::unique_ptr<SimplifiedObb> builder;
      const double once = median_ms(1, [&] { builder = std::make_unique<SimplifiedObb>(mesh, settings); });
      // Per update at a moving pose, as the obstacle is rebuilt every step.
      int step = 0;
      const double per = median_ms(runs, [&] {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.rotate(Eigen::AngleAxisd(0.01 * step++, Eigen::Vector3d::UnitY()));
        box = builder->update(pose);
      });
      rows.push_back({label, per, once, builder->update(Eigen::Isometry3d::Identity()).volume()});
    }
    rows.push_back({"tight (ours)", t_tight, 0, tight.volume()});
    rows.push_back({"cgal optimal", t_cgal, 0, cgal_volume});
    for (const Row& r : rows) {
      std::printf("%-9s %-26s %10.3f %10.1f %8.3f %8.3f %8.3f\n", name, r.method.c_str(), r.time, r.once,
                  r.volume / model_volume, r.volume / tight.volume(), r.volume / cgal_volume);
      csv << name << ',' << mesh.face_count() << ",\"" << r.method << "\"," << r.time << ',' << r.once << ','
          << r.volume << ',' << r.volume / model_volume << ',' << r.volume / tight.volume() << ','
          << r.volume / cgal_volume << '\n';
    }
    // Chart bars: AABB, (a) covariance, (b) eqs. 11-18, (b) + refine, (c) + refine.
    chart.push_back({rows[0].volume / tight.volume(), rows[2].volume / tight.volume(), rows[3].volume / tight.volume(),
                     rows[4].volume / tight.volume(), rows[6].volume / tight.volume()});
    const double a = rows[2].time, c = rows[6].time;
    std::printf("%-9s (c)+refine per update is %.2fx faster than (a); with the one-off simplification spread over 100 "
                "steps %.2fx\n",
                name, a / c, a / (c + rows[6].once / 100));
  }
  write_chart(out / "geometry_obb_tightness.png", chart);
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path models = default_model_dir();
  std::filesystem::path out = "bench/results";
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--models" && i + 1 < argc) models = argv[++i];
    else if (arg == "--out" && i + 1 < argc) out = argv[++i];
    else if (arg == "--quick") quick = true;
    else {
      std::cerr << "usage: clothcd_bench_geometry [--models DIR] [--out DIR] [--quick]\n";
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(out);
    bench_qem(models, out, quick);
    bench_obb(models, out, quick);
  } catch (const std::exception& e) {
    std::cerr << "clothcd_bench_geometry: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
