// `clothcd detect T0_MESH T1_MESH`: continuous collision detection of one step of a deformable mesh against itself
// (the obstacle may be part of the same mesh); prints counts and stage times, or with --json (and into --out) every
// collision with its normal, barycentric weights or edge parameters and bodies. The JSON report is written as it is
// serialised, one collision at a time, never held whole in memory. A step with more collisions than --max-collisions
// ends with the detector's one-line error and exit code 1.
// `--filter network` runs the detector's network culling (the pair network in front of the combined filters).
// `--earliest` answers the other question of a step instead: its earliest time of impact and the pair that sets it
// (CollisionDetector::earliest_impact), the collision-free fraction of the step.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "commands.hpp"
#include "face_names.hpp"
#include "json_stream.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct DetectOptions {
  std::string t0_path;
  std::string t1_path;
  double thickness = 0.0;
  bool approximate = false;
  std::string bvh = "sphere-root-aabb";
  std::string filter = "combined";
  std::string network;
  std::string out;
  bool json = false;
  bool earliest = false;
  long max_collisions = DetectorSettings{}.max_collisions;
};

// One collision's JSON: its pair (vertex and face index, or two edges), body of each vertex, time of impact, the
// barycentric weights (vertex-face) or edge parameters (edge-edge), the contact normal, and whether it is conservative.
Json collision_json(const Collision& c, int face) {
  Json item;
  if (c.kind == PairKind::VertexFace) {
    item["pair"] = {c.vertices[0].vertex, face};
    item["face_vertices"] = {c.vertices[1].vertex, c.vertices[2].vertex, c.vertices[3].vertex};
    item["barycentric"] = {1.0 - c.parameters[0] - c.parameters[1], c.parameters[0], c.parameters[1]};
  } else {
    item["pair"] = {{c.vertices[0].vertex, c.vertices[1].vertex}, {c.vertices[2].vertex, c.vertices[3].vertex}};
    item["edge_parameters"] = {c.parameters[0], c.parameters[1]};
  }
  item["bodies"] = {c.vertices[0].body, c.vertices[1].body, c.vertices[2].body, c.vertices[3].body};
  item["toi"] = c.toi;
  item["normal"] = json_vector(c.normal);
  item["conservative"] = c.conservative;
  return item;
}

// The report's fields before the collisions.
Json detect_json_head(const DetectOptions& o, const TriangleMesh& mesh, const std::vector<Collision>& collisions,
                      const DetectionStats& s, double load_ms) {
  const auto vertex_face = static_cast<std::size_t>(std::count_if(
      collisions.begin(), collisions.end(), [](const Collision& c) { return c.kind == PairKind::VertexFace; }));
  Json report = json_report("detect");
  report["t0"] = o.t0_path;
  report["t1"] = o.t1_path;
  report["vertices"] = mesh.vertex_count();
  report["faces"] = mesh.face_count();
  report["thickness"] = o.thickness;
  report["exact"] = !o.approximate;
  report["bvh"] = o.bvh;
  report["filter"] = o.filter;
  report["counts"] = {{"candidates_vertex_face", s.candidates_vertex_face},
                      {"candidates_edge_edge", s.candidates_edge_edge},
                      {"culled", s.culled},
                      {"vertex_face", vertex_face},
                      {"edge_edge", collisions.size() - vertex_face}};
  report["times_ms"] = {{"load", milliseconds(load_ms)},       {"refit", milliseconds(s.refit_ms)},
                        {"traversal", milliseconds(s.traversal_ms)}, {"filters", milliseconds(s.culling_ms)},
                        {"exact", milliseconds(s.exact_ms)}};
  if (o.filter == "network")
    report["network"] = {{"dropped", s.network_dropped},          {"overruled", s.network_overruled},
                         {"kept", s.network_kept},                {"network_ms", milliseconds(s.network_ms)},
                         {"filters_ms", milliseconds(s.network_filters_ms)}};
  return report;
}

// Writes the report: the head with the "vertex_face" and "edge_edge" arrays appended.
void write_detect_json(std::ostream& out, const Json& head, const TriangleMesh& mesh,
                       const std::vector<Collision>& collisions) {
  JsonStream stream(out, head);
  FaceNames faces(mesh);
  for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
    stream.array(kind == PairKind::VertexFace ? "vertex_face" : "edge_edge", [&](const auto& write) {
      for (const Collision& c : collisions) {
        if (c.kind == kind) write(collision_json(c, kind == PairKind::VertexFace ? faces.next(c.vertices) : -1));
      }
    });
  }
  stream.close();
}

// --earliest: the step's earliest time of impact and the pair that sets it.
void report_earliest(const DetectOptions& o, CollisionDetector& detector, const MeshFrames& frames, double load_ms) {
  const EarliestImpact e = detector.earliest_impact(frames.start.vertices, frames.end);
  const DetectionStats& s = detector.stats();
  const TriangleMesh& t0 = frames.start;
  if (o.json || !o.out.empty()) {
    Json report = detect_json_head(o, t0, {}, s, load_ms);
    report["counts"].erase("vertex_face");  // no collision list: the earliest pair only
    report["counts"].erase("edge_edge");
    FaceNames faces(t0);
    report["earliest"] = {{"toi", e.toi},
                          {"hit", e.hit},
                          {"windows", e.windows},
                          {"pair", e.hit ? collision_json(e.pair, e.pair.kind == PairKind::VertexFace ? faces.next(e.pair.vertices)
                                                                                                       : -1)
                                         : Json(nullptr)}};
    write_to(o.json, o.out, [&](std::ostream& out) { out << report.dump(2) << '\n'; });
    if (o.json) return;
  }
  std::cout << "mesh:        " << t0.vertex_count() << " vertices, " << t0.face_count() << " faces (one deformable "
            << "body with self-collision)\n"
            << "candidates:  " << s.candidates_vertex_face << " vertex-face, " << s.candidates_edge_edge
            << " edge-edge (" << o.bvh << ", " << e.windows << (e.windows == 1 ? " window" : " windows") << ")\n"
            << std::setprecision(17) << "earliest:    toi " << e.toi;
  if (e.hit) {
    const auto& v = e.pair.vertices;
    if (e.pair.kind == PairKind::VertexFace) {
      std::cout << ", vertex " << v[0].vertex << " against face (" << v[1].vertex << ", " << v[2].vertex << ", "
                << v[3].vertex << ")\n";
    } else {
      std::cout << ", edge (" << v[0].vertex << ", " << v[1].vertex << ") against edge (" << v[2].vertex << ", "
                << v[3].vertex << ")\n";
    }
  } else {
    std::cout << " (no contact during the step)\n";
  }
  std::cout << std::fixed << std::setprecision(3) << "times (ms):  load " << load_ms << ", build+refit " << s.refit_ms
            << ", traversal " << s.traversal_ms << ", filters " << s.culling_ms << ", exact " << s.exact_ms << '\n';
  if (!o.out.empty()) std::cout << "wrote " << o.out << '\n';
}

void run_detect(const DetectOptions& o) {
  check_network_needs_filter(o.network, o.filter);
  check_approximate_needs_zero_thickness(o.approximate, o.thickness);
  if (!o.out.empty()) check_output_file(o.out, "--out");
  DetectorSettings settings;
  settings.hierarchy = hierarchy_named(o.bvh);
  settings.culling = culling_named(o.filter);
  learning::attach_network_culler(settings, o.network);
  settings.thickness = o.thickness;
  settings.decide_exactly = !o.approximate;
  settings.max_collisions = o.max_collisions;

  const auto t = std::chrono::steady_clock::now();
  const MeshFrames frames = load_mesh_frames(o.t0_path, o.t1_path);
  const TriangleMesh& t0 = frames.start;
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();

  CollisionDetector detector(t0.faces, static_cast<int>(t0.vertex_count()), settings);
  if (o.earliest) {
    report_earliest(o, detector, frames, load_ms);
    return;
  }
  const std::vector<Collision>& collisions = detector.detect(t0.vertices, frames.end);
  const DetectionStats& s = detector.stats();
  if (o.json || !o.out.empty()) {
    const Json head = detect_json_head(o, t0, collisions, s, load_ms);
    write_to(o.json, o.out, [&](std::ostream& out) { write_detect_json(out, head, t0, collisions); });
    if (o.json) return;
  }
  long vf = 0;
  for (const Collision& c : collisions) vf += c.kind == PairKind::VertexFace ? 1 : 0;
  std::cout << "mesh:        " << t0.vertex_count() << " vertices, " << t0.face_count() << " faces (one deformable "
            << "body with self-collision)\n"
            << "candidates:  " << s.candidates_vertex_face << " vertex-face, " << s.candidates_edge_edge
            << " edge-edge (" << o.bvh << ")\n"
            << "culled:      " << s.culled << " (" << o.filter << ")\n"
            << "collisions:  " << vf << " vertex-face, " << collisions.size() - vf << " edge-edge\n"
            << std::fixed << std::setprecision(3) << "times (ms):  load " << load_ms << ", build+refit "
            << s.refit_ms << ", traversal " << s.traversal_ms << ", filters " << s.culling_ms << ", exact "
            << s.exact_ms << '\n';
  if (o.filter == "network") {
    std::cout << "network:     " << s.network_dropped << " dropped (confirmed by the filters), " << s.network_overruled
              << " drops overruled, " << s.network_kept << " kept; features+inference " << s.network_ms
              << " ms, filters " << s.network_filters_ms << " ms\n";
  }
  if (!o.out.empty()) std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void add_detect_command(CLI::App& app) {
  auto* command = app.add_subcommand("detect", "Continuous collision detection between two frames of one mesh");
  auto o = std::make_shared<DetectOptions>();
  command->add_option("T0_MESH", o->t0_path, "Mesh at the start of the step")->required();
  command->add_option("T1_MESH", o->t1_path, "Same mesh (same faces) at the end of the step")->required();
  command->add_option("--thickness", o->thickness, "Minimum separation, in mesh units")
      ->check(finite_number(0.0, std::numeric_limits<double>::infinity()));
  add_approximate_flag(*command, o->approximate,
                       "Thickness 0 only: report the pairs the floating-point fast tier leaves undecided as "
                       "conservative hits (toi a lower bound) instead of deciding them exactly");
  add_bvh_option(*command, o->bvh);
  add_filter_option(*command, o->filter);
  add_network_option(*command, o->network, "--model");
  add_json_flag(*command, o->json);
  command->add_option("--out", o->out, "Also write the JSON report (every collision and the stage times) to this file");
  command->add_option("--max-collisions", o->max_collisions,
                      "Collision budget: a step with more collisions stops early with an error (exit code 1)")
      ->check(CLI::Range(1L, kLargestCollisionBudget));
  command->add_flag("--earliest", o->earliest,
                    "Report the step's earliest time of impact (1: no contact) and the pair that sets it, instead of "
                    "every collision");
  command->callback([o] { run_detect(*o); });
}

}  // namespace clothcd::cli
