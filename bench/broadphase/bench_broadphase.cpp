// Broad phase and whole-detection benchmark (Jin et al., section 3.2 and Tables 5 and 7), with FCL 0.7's AABB BVH
// measured in the same run as the peer.
//  1. cloth C (4,802 triangles) moving down through the human: refit + cloth-vs-obstacle candidate search, per step,
//     ours (each hierarchy) vs FCL (BVHModel<AABB> update + refit, then collide with every contact);
//  2. cloth C self candidates: ours vs FCL's naive self query (every overlapping triangle pair, adjacent ones included);
//  3. whole detection (broad + filters + exact, obstacle + self, VF + EE) for cloth C draped on the human;
//  4. Table 5/7 style rows: cloths A, B, C draped on the bird, sphere, cube and fish, each hierarchy;
//  5. scaling: cloth grids of 5k to 200k triangles draped on a sphere, time per triangle.
// Single thread unless a row says otherwise. Writes CSV files under the results folder.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "clothcd/broadphase/body_topology.hpp"
#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/broadphase/swept_boxes.hpp"
#include "clothcd/broadphase/traversal.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"

using namespace clothcd;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

const char* hierarchy_name(HierarchyKind k) {
  switch (k) {
    case HierarchyKind::SphereRootAabb: return "sphere-root-aabb";
    case HierarchyKind::Aabb: return "aabb";
    case HierarchyKind::AabbObb: return "aabb-obb";
  }
  return "?";
}

// A cloth in the plane orthogonal to `up` (0 = x, 1 = y, 2 = z), centred on (cx, cy, cz) of the obstacle's box.
TriangleMesh place_cloth(TriangleMesh cloth, int up, const Eigen::Vector3d& centre, double height) {
  for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
    const double a = cloth.vertices(v, 0), b = cloth.vertices(v, 2);
    Eigen::Vector3d p = centre;
    p[up] = height;
    p[(up + 1) % 3] += a;
    p[(up + 2) % 3] += b;
    cloth.vertices.row(v) = p.transpose();
  }
  return cloth;
}

// Highest hit of a vertical ray (along -up) through (u, w) with the mesh, -inf when it misses (Moller-Trumbore in 2D
// with barycentric interpolation of the height).
double surface_height(const TriangleMesh& mesh, int up, double u, double w) {
  const int iu = (up + 1) % 3, iw = (up + 2) % 3;
  double best = -std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    const double d = (b[iu] - a[iu]) * (c[iw] - a[iw]) - (c[iu] - a[iu]) * (b[iw] - a[iw]);
    if (std::abs(d) < 1e-300) continue;
    const double l1 = ((u - a[iu]) * (c[iw] - a[iw]) - (c[iu] - a[iu]) * (w - a[iw])) / d;
    const double l2 = ((b[iu] - a[iu]) * (w - a[iw]) - (u - a[iu]) * (b[iw] - a[iw])) / d;
    if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
    best = std::max(best, a[up] + l1 * (b[up] - a[up]) + l2 * (c[up] - a[up]));
  }
  return best;
}

// The cloth dropped straight down onto the obstacle: each vertex rests `gap` above the highest surface point below it,
// but no lower than `floor` (vertices beside the obstacle hang at the floor).
void drape(TriangleMesh& cloth, const TriangleMesh& obstacle, int up, double gap, double floor) {
  const int iu = (up + 1) % 3, iw = (up + 2) % 3;
  for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
    const double h = surface_height(obstacle, up, cloth.vertices(v, iu), cloth.vertices(v, iw));
    cloth.vertices(v, up) = std::max(h, floor) + gap;
  }
}

struct Bounds {
  Eigen::Vector3d min, max;
};
Bounds bounds(const TriangleMesh& m) {
  return {m.vertices.colwise().minCoeff().transpose(), m.vertices.colwise().maxCoeff().transpose()};
}

// ---------- FCL peer ----------
using FclModel = fcl::BVHModel<fcl::AABBd>;

std::vector<fcl::Vector3d> fcl_points(const Vertices& v) {
  std::vector<fcl::Vector3d> p(v.rows());
  for (Eigen::Index i = 0; i < v.rows(); ++i) p[i] = v.row(i).transpose();
  return p;
}

std::shared_ptr<FclModel> fcl_model(const TriangleMesh& mesh) {
  std::vector<fcl::Triangle> triangles(mesh.face_count());
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    triangles[f] = fcl::Triangle(mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2));
  }
  auto model = std::make_shared<FclModel>();
  model->beginModel();
  model->addSubModel(fcl_points(mesh.vertices), triangles);
  model->endModel();
  return model;
}

std::size_t fcl_collide(const std::shared_ptr<FclModel>& a, const std::shared_ptr<FclModel>& b) {
  fcl::CollisionObjectd oa(a), ob(b);
  fcl::CollisionRequestd request(100000000, false);
  fcl::CollisionResultd result;
  fcl::collide(&oa, &ob, request, result);
  return result.numContacts();
}

// ---------- ours: one body with its hierarchy ----------
struct OurBody {
  broadphase::BodyTopology topology;
  broadphase::SweptBoxes boxes;
  broadphase::Bvh bvh;
  OurBody(const TriangleMesh& mesh, broadphase::VolumeKind kind)
      : topology(broadphase::build_body_topology(mesh.faces, static_cast<int>(mesh.vertex_count()))),
        bvh(broadphase::BvhSettings{kind, 2, 2.0}) {
    broadphase::compute_swept_boxes(topology, mesh.vertices, mesh.vertices, 0.0, boxes);
    bvh.build(topology, boxes, mesh.vertices, mesh.vertices);
  }
  void step(const Vertices& start, const Vertices& end) {
    broadphase::compute_swept_boxes(topology, start, end, 0.0, boxes);
    bvh.update(topology, boxes, start, end);
  }
  broadphase::BodyView view(int body) const { return {body, &topology, &boxes, &bvh}; }
};

struct Csv {
  std::ofstream file;
  Csv(const std::filesystem::path& path, const std::string& header) : file(path) { file << header << '\n'; }
};

// 1 and 2: cloth C moving down through the human.
void bench_moving_cloth(const TriangleMesh& human, const std::filesystem::path& out_dir) {
  const Bounds b = bounds(human);
  const int up = 2;
  const Eigen::Vector3d centre = 0.5 * (b.min + b.max);
  const double size = 1.3 * (b.max[0] - b.min[0]);
  const int steps = 200;
  const double top = b.max[up] + 0.2, bottom = b.min[up] - 0.2;
  const double dz = (top - bottom) / steps;
  const TriangleMesh cloth0 = place_cloth(make_paper_cloth('C', size), up, centre, top);
  auto frame = [&](int s) {
    Vertices v = cloth0.vertices;
    v.col(up).array() -= dz * s;
    return v;
  };

  Csv csv(out_dir / "broadphase_moving_cloth.csv",
          "method,refit_ms,obstacle_search_ms,refit_plus_search_ms,self_search_ms,obstacle_pairs_per_step,"
          "self_pairs_per_step");
  std::cout << "\n== 1/2. cloth C (" << cloth0.face_count() << " t) moving through human-blend (" << human.face_count()
            << " t), " << steps << " steps, single thread ==\n";
  std::cout << std::fixed << std::setprecision(4);

  // FCL.
  double fcl_refit = 0, fcl_search = 0, fcl_self = 0;
  std::size_t fcl_pairs = 0, fcl_self_pairs = 0;
  {
    auto cloth = fcl_model(cloth0);
    auto obstacle = fcl_model(human);
    for (int s = 1; s <= steps; ++s) {
      const auto points = fcl_points(frame(s));
      auto t = Clock::now();
      cloth->beginUpdateModel();
      cloth->updateSubModel(points);
      cloth->endUpdateModel(true, true);
      fcl_refit += ms_since(t);
      t = Clock::now();
      fcl_pairs += fcl_collide(cloth, obstacle);
      fcl_search += ms_since(t);
      if (s % 20 == 0) {
        t = Clock::now();
        fcl_self_pairs += fcl_collide(cloth, cloth);
        fcl_self += ms_since(t);
      }
    }
  }
  const double fcl_total = (fcl_refit + fcl_search) / steps;
  std::cout << "FCL AABB: refit " << fcl_refit / steps << " ms, cloth-vs-obstacle " << fcl_search / steps
            << " ms (" << fcl_pairs / steps << " triangle pairs/step), self (naive) " << fcl_self / (steps / 20)
            << " ms (" << fcl_self_pairs / (steps / 20) << " pairs)\n";
  csv.file << "fcl-aabb," << fcl_refit / steps << ',' << fcl_search / steps << ',' << fcl_total << ','
           << fcl_self / (steps / 20) << ',' << fcl_pairs / steps << ',' << fcl_self_pairs / (steps / 20) << '\n';

  const std::pair<broadphase::VolumeKind, broadphase::VolumeKind> kinds[] = {
      {broadphase::VolumeKind::Sphere, broadphase::VolumeKind::Sphere},
      {broadphase::VolumeKind::Aabb, broadphase::VolumeKind::Aabb},
      {broadphase::VolumeKind::Aabb, broadphase::VolumeKind::Obb}};
  const char* names[] = {"ours-sphere-root-aabb", "ours-aabb", "ours-aabb-obb"};
  for (int k = 0; k < 3; ++k) {
    OurBody cloth(cloth0, kinds[k].first);
    OurBody obstacle(human, kinds[k].second);
    broadphase::CandidateSet candidates;
    double refit = 0, search = 0, self = 0;
    std::size_t pairs = 0, self_pairs = 0;
    broadphase::TraversalStats self_stats;
    for (int s = 1; s <= steps; ++s) {
      const Vertices start = frame(s - 1), end = frame(s);
      auto t = Clock::now();
      cloth.step(start, end);
      refit += ms_since(t);
      t = Clock::now();
      candidates.clear();
      broadphase::find_pair_candidates(cloth.view(0), obstacle.view(1), {false}, candidates);
      search += ms_since(t);
      pairs += candidates.size();
      if (s % 20 == 0) {
        candidates.clear();
        t = Clock::now();
        broadphase::find_self_candidates(cloth.view(0), {false}, candidates, &self_stats);
        self += ms_since(t);
        self_pairs += candidates.size();
      }
    }
    const double total = (refit + search) / steps;
    std::cout << names[k] << ": refit " << refit / steps << " ms, cloth-vs-obstacle " << search / steps << " ms ("
              << pairs / steps << " primitive pairs/step), refit+search " << total << " ms = " << fcl_total / total
              << "x faster than FCL; self " << self / (steps / 20) << " ms (" << self_pairs / (steps / 20)
              << " VF+EE pairs, " << self_stats.volume_tests / (steps / 20) << " volume tests, "
              << self_stats.primitive_tests / (steps / 20) << " primitive tests) = " << fcl_self / self
              << "x faster than FCL naive self\n";
    csv.file << names[k] << ',' << refit / steps << ',' << search / steps << ',' << total << ','
             << self / (steps / 20) << ',' << pairs / steps << ',' << self_pairs / (steps / 20) << '\n';
  }
}

struct DetectTiming {
  double per_step_ms = 0;
  double refit = 0, traversal = 0, culling = 0, exact = 0;
  long candidates = 0, collisions = 0;
};

// Steps of a draped cloth settling by `drop` per step onto `obstacle`; the detector's stage times averaged.
DetectTiming time_detection(const TriangleMesh& cloth, const TriangleMesh& obstacle, int up, double drop, int steps,
                            HierarchyKind hierarchy, bool parallel) {
  DetectorSettings settings;
  settings.hierarchy = hierarchy;
  settings.parallel = parallel;
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  detector.add_obstacle(obstacle);
  Vertices start = cloth.vertices;
  detector.detect(start, start);  // builds the hierarchies (not timed)
  DetectTiming timing;
  for (int s = 0; s < steps; ++s) {
    Vertices end = start;
    end.col(up).array() -= drop;
    const auto t = Clock::now();
    detector.detect(start, end);
    timing.per_step_ms += ms_since(t);
    const DetectionStats& st = detector.stats();
    timing.refit += st.refit_ms;
    timing.traversal += st.traversal_ms;
    timing.culling += st.culling_ms;
    timing.exact += st.exact_ms;
    timing.candidates += st.candidates_vertex_face + st.candidates_edge_edge;
    timing.collisions += st.collisions;
    start = end;
  }
  for (double* x : {&timing.per_step_ms, &timing.refit, &timing.traversal, &timing.culling, &timing.exact}) *x /= steps;
  timing.candidates /= steps;
  timing.collisions /= steps;
  return timing;
}

TriangleMesh draped_cloth(char name, const TriangleMesh& obstacle, int up, double cover, double gap_ratio) {
  const Bounds b = bounds(obstacle);
  const Eigen::Vector3d centre = 0.5 * (b.min + b.max);
  const double extent = std::max(b.max[(up + 1) % 3] - b.min[(up + 1) % 3], b.max[(up + 2) % 3] - b.min[(up + 2) % 3]);
  const double size = cover * extent;
  TriangleMesh cloth = place_cloth(make_paper_cloth(name, size), up, centre, b.max[up]);
  const double height = b.max[up] - b.min[up];
  drape(cloth, obstacle, up, gap_ratio * size, b.max[up] - 0.35 * height);
  return cloth;
}

void print_timing(std::ostream& os, const std::string& label, const DetectTiming& t) {
  os << label << ": " << t.per_step_ms << " ms/step (refit " << t.refit << ", traversal " << t.traversal
     << ", filters " << t.culling << ", exact " << t.exact << "), " << t.candidates << " candidates, " << t.collisions
     << " collisions per step\n";
}

void bench_draped_human(const TriangleMesh& human, const std::filesystem::path& out_dir) {
  const int up = 2;
  const TriangleMesh cloth = draped_cloth('C', human, up, 1.1, 0.002);
  const double size = 1.1 * (bounds(human).max[0] - bounds(human).min[0]);
  std::cout << "\n== 3. whole detection, cloth C draped on human-blend, settling " << 0.001 * size
            << " per step (broad + filters + exact, obstacle + self, VF + EE) ==\n";
  Csv csv(out_dir / "detection_draped_human.csv",
          "hierarchy,threads,ms_per_step,refit_ms,traversal_ms,filters_ms,exact_ms,candidates,collisions");
  for (HierarchyKind k : {HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb}) {
    for (bool parallel : {false, true}) {
      tbb::global_control threads(tbb::global_control::max_allowed_parallelism, parallel ? 2 : 1);
      const DetectTiming t = time_detection(cloth, human, up, 0.001 * size, 30, k, parallel);
      print_timing(std::cout, std::string(hierarchy_name(k)) + (parallel ? " (2 threads)" : " (1 thread)"), t);
      csv.file << hierarchy_name(k) << ',' << (parallel ? 2 : 1) << ',' << t.per_step_ms << ',' << t.refit << ','
               << t.traversal << ',' << t.culling << ',' << t.exact << ',' << t.candidates << ',' << t.collisions
               << '\n';
    }
  }
}

void bench_tables(const std::filesystem::path& model_dir, const std::filesystem::path& out_dir) {
  std::cout << "\n== 4. Table 5/7 style: cloths draped on the models, whole detection per step, single thread ==\n";
  Csv csv(out_dir / "detection_tables_5_7.csv",
          "cloth,model,hierarchy,ms_per_step,refit_ms,traversal_ms,filters_ms,exact_ms,candidates,collisions,"
          "double_box_vs_hybrid_pct");
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  for (const std::string model : {"bird", "sphere", "cube", "fish"}) {
    const TriangleMesh obstacle = load_mesh(fetch_model(model, model_dir));
    for (char cloth_name : {'A', 'B', 'C'}) {
      const TriangleMesh cloth = draped_cloth(cloth_name, obstacle, 1, 1.3, 0.002);
      const Bounds b = bounds(obstacle);
      const double drop = 0.0013 * (b.max[0] - b.min[0]);
      std::map<HierarchyKind, DetectTiming> t;
      for (HierarchyKind k : {HierarchyKind::Aabb, HierarchyKind::AabbObb, HierarchyKind::SphereRootAabb}) {
        t[k] = time_detection(cloth, obstacle, 1, drop, 20, k, false);
      }
      const double gain = 100.0 * (1.0 - t[HierarchyKind::SphereRootAabb].per_step_ms /
                                             t[HierarchyKind::AabbObb].per_step_ms);
      std::cout << "cloth " << cloth_name << " / " << std::setw(6) << model << ": AABB "
                << t[HierarchyKind::Aabb].per_step_ms << " ms, AABB-OBB " << t[HierarchyKind::AabbObb].per_step_ms
                << " ms, double box " << t[HierarchyKind::SphereRootAabb].per_step_ms
                << " ms; double box vs hybrid: " << gain << "% faster (" << t[HierarchyKind::Aabb].candidates
                << " candidates, " << t[HierarchyKind::Aabb].collisions << " collisions)\n";
      for (auto& [k, x] : t) {
        csv.file << cloth_name << ',' << model << ',' << hierarchy_name(k) << ',' << x.per_step_ms << ',' << x.refit
                 << ',' << x.traversal << ',' << x.culling << ',' << x.exact << ',' << x.candidates << ','
                 << x.collisions << ',' << gain << '\n';
      }
    }
  }
}

void bench_scaling(const std::filesystem::path& out_dir) {
  std::cout << "\n== 5. scaling: square cloths draped on a UV sphere (radius 1, 5,120 t), single thread ==\n";
  Csv csv(out_dir / "detection_scaling.csv",
          "cloth_triangles,hierarchy,ms_per_step,us_per_triangle,broad_ms,filters_ms,exact_ms,candidates,collisions");
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const TriangleMesh sphere = make_uv_sphere(1.0, 80, 33);
  std::map<HierarchyKind, double> base;
  for (int n : {51, 101, 159, 224, 317}) {
    TriangleMesh cloth = make_grid(n, n, 3.0, 3.0);
    for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
      const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2), r2 = x * x + z * z;
      cloth.vertices(v, 1) = (r2 < 1.0 ? std::sqrt(1.0 - r2) : 0.0) + 0.003;
    }
    for (HierarchyKind k : {HierarchyKind::SphereRootAabb, HierarchyKind::Aabb, HierarchyKind::AabbObb}) {
      const DetectTiming t = time_detection(cloth, sphere, 1, 0.0015, 10, k, false);
      const double per_triangle = 1000.0 * t.per_step_ms / cloth.face_count();
      if (n == 51) base[k] = per_triangle;
      std::cout << cloth.face_count() << " t, " << hierarchy_name(k) << ": " << t.per_step_ms << " ms/step, "
                << per_triangle << " us/triangle (" << per_triangle / base[k] << "x the 5k cost), broad "
                << t.refit + t.traversal << " ms, " << t.candidates << " candidates\n";
      csv.file << cloth.face_count() << ',' << hierarchy_name(k) << ',' << t.per_step_ms << ',' << per_triangle << ','
               << t.refit + t.traversal << ',' << t.culling << ',' << t.exact << ',' << t.candidates << ','
               << t.collisions << '\n';
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out_dir = argc > 1 ? argv[1] : "bench/results";
  const std::filesystem::path model_dir = argc > 2 ? argv[2] : default_model_dir();
  const std::string only = argc > 3 ? argv[3] : "all";
  std::filesystem::create_directories(out_dir);
  try {
    const TriangleMesh human = load_mesh(fetch_model("human-blend", model_dir));
    {
      tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
      if (only == "all" || only == "moving") bench_moving_cloth(human, out_dir);
    }
    if (only == "all" || only == "draped") bench_draped_human(human, out_dir);
    if (only == "all" || only == "tables") bench_tables(model_dir, out_dir);
    if (only == "all" || only == "scaling") bench_scaling(out_dir);
  } catch (const std::exception& e) {
    std::cerr << "bench_broadphase: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
