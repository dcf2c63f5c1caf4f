// `clothcd intersections MESH`: the intersecting face pairs of one state of a mesh (one body against itself,
// CollisionDetector::intersections), each with a point where an edge of one face meets the other; prints counts and
// stage times, or with --json (and into --out) every pair, written one pair at a time. `--free` answers only whether
// the mesh is intersection-free (CollisionDetector::is_intersection_free, which stops at the first pair); the exit
// code is 0 either way.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "json_stream.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"
#include "state_json.hpp"

namespace clothcd::cli {
namespace {

struct IntersectionsOptions {
  std::string mesh_path;
  std::string bvh = "sphere-root-aabb";
  std::string out;
  bool json = false;
  bool free = false;
  long max_collisions = DetectorSettings{}.max_collisions;
};

void run_intersections(const IntersectionsOptions& o) {
  if (!o.out.empty()) check_output_file(o.out, "--out");
  double load_ms = 0.0;
  const TriangleMesh mesh = load_state_mesh(o.mesh_path, load_ms);
  CollisionDetector detector = state_detector(mesh, o.bvh, o.max_collisions);
  const bool free = o.free && detector.is_intersection_free(mesh.vertices);
  const std::vector<FaceIntersection> none;
  const std::vector<FaceIntersection>& pairs = o.free ? none : detector.intersections(mesh.vertices);
  const DetectionStats& s = detector.stats();
  const long coplanar = std::count_if(pairs.begin(), pairs.end(), [](const FaceIntersection& x) { return x.coplanar; });
  if (o.json || !o.out.empty()) {
    Json head = json_report("intersections");
    head["mesh"] = o.mesh_path;
    head["vertices"] = mesh.vertex_count();
    head["faces"] = mesh.face_count();
    head["bvh"] = o.bvh;
    head["intersection_free"] = o.free ? free : pairs.empty();
    head["counts"] = {{"candidates", s.candidates_vertex_face}};
    if (!o.free) {
      head["counts"]["intersections"] = pairs.size();
      head["counts"]["coplanar"] = coplanar;
    }
    head["times_ms"] = state_times_json(load_ms, s);
    write_to(o.json, o.out, [&](std::ostream& out) {
      JsonStream stream(out, head);
      if (!o.free) {
        stream.array("intersections", [&](const auto& write) {
          for (const FaceIntersection& x : pairs) write(intersection_json(x));
        });
      }
      stream.close();
    });
    if (o.json) return;
  }
  std::cout << "mesh:          " << mesh.vertex_count() << " vertices, " << mesh.faces.rows() << " faces (one body "
            << "with self-collision)\n"
            << "candidates:    " << s.candidates_vertex_face << " face pairs (" << o.bvh << ")\n";
  if (o.free) {
    std::cout << "intersection-free: " << (free ? "yes" : "no") << '\n';
  } else {
    std::cout << "intersections: " << pairs.size() << " face pairs (" << coplanar << " coplanar)\n";
  }
  std::cout << std::fixed << std::setprecision(3) << "times (ms):    load " << load_ms << ", build+refit "
            << s.refit_ms << ", traversal " << s.traversal_ms << ", exact " << s.exact_ms << '\n';
  if (!o.out.empty()) std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void add_intersections_command(CLI::App& app) {
  auto* command = app.add_subcommand("intersections", "Intersecting face pairs of one mesh (against itself)");
  auto o = std::make_shared<IntersectionsOptions>();
  command->add_option("MESH", o->mesh_path, "The mesh (one body, against itself)")->required();
  add_bvh_option(*command, o->bvh);
  add_json_flag(*command, o->json);
  command->add_option("--out", o->out, "Also write the JSON report (every pair and the stage times) to this file");
  command->add_option("--max-collisions", o->max_collisions,
                      "Pair budget: more intersecting pairs stop the search with an error (exit code 1)")
      ->check(CLI::Range(1L, kLargestCollisionBudget));
  command->add_flag("--free", o->free,
                    "Only say whether the mesh is intersection-free (stops at the first pair; exit code 0 either way)");
  command->callback([o] { run_intersections(*o); });
}

}  // namespace clothcd::cli
