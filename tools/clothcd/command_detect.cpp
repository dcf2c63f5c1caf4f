// `clothcd detect T0_MESH T1_MESH`: continuous collision detection of one step of a deformable mesh against itself
// (the obstacle may be part of the same mesh); prints counts and stage times, or with --json (and into --out) every
// collision with its normal, barycentric weights or edge parameters and bodies.
// `--filter network` runs the detector's network culling (the pair network in front of the combined filters).
#include <array>
#include <cmath>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <stdexcept>
#include <sstream>
#include <string>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/learning/network_culler.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "commands.hpp"
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
};

// The face index of each vertex-face collision (collisions name the face by its three vertices): a face listed
// several times in the mesh is several faces with the same vertices, named in turn for each vertex that hits them.
std::vector<int> collision_faces(const TriangleMesh& mesh, const std::vector<Collision>& collisions) {
  std::map<std::array<int, 3>, std::vector<int>> faces_of;
  for (int f = 0; f < static_cast<int>(mesh.face_count()); ++f) {
    faces_of[{mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)}].push_back(f);
  }
  std::map<std::pair<int, std::array<int, 3>>, std::size_t> named;  // (vertex, face vertices) -> faces named so far
  std::vector<int> faces;
  for (const Collision& c : collisions) {
    if (c.kind != PairKind::VertexFace) continue;
    const std::array<int, 3> key{c.vertices[1].vertex, c.vertices[2].vertex, c.vertices[3].vertex};
    const std::vector<int>& candidates = faces_of.at(key);
    std::size_t& next = named[{c.vertices[0].vertex, key}];
    faces.push_back(candidates[std::min(next, candidates.size() - 1)]);
    ++next;
  }
  return faces;
}

// A time in milliseconds to the microsecond (the full 17 digits of the other numbers say nothing here).
double milliseconds(double ms) { return std::round(ms * 1000.0) / 1000.0; }

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

Json detect_json(const DetectOptions& o, const TriangleMesh& mesh, const std::vector<Collision>& collisions,
                 const DetectionStats& s, double load_ms) {
  const std::vector<int> faces = collision_faces(mesh, collisions);
  Json vertex_face = Json::array(), edge_edge = Json::array();
  std::size_t vertex_face_index = 0;
  for (const Collision& c : collisions) {
    if (c.kind == PairKind::VertexFace)
      vertex_face.push_back(collision_json(c, faces[vertex_face_index++]));
    else
      edge_edge.push_back(collision_json(c, -1));
  }
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
                      {"vertex_face", vertex_face.size()},
                      {"edge_edge", edge_edge.size()}};
  report["times_ms"] = {{"load", milliseconds(load_ms)},       {"refit", milliseconds(s.refit_ms)},
                        {"traversal", milliseconds(s.traversal_ms)}, {"filters", milliseconds(s.culling_ms)},
                        {"exact", milliseconds(s.exact_ms)}};
  if (o.filter == "network")
    report["network"] = {{"dropped", s.network_dropped},          {"overruled", s.network_overruled},
                         {"kept", s.network_kept},                {"network_ms", milliseconds(s.network_ms)},
                         {"filters_ms", milliseconds(s.network_filters_ms)}};
  report["vertex_face"] = std::move(vertex_face);
  report["edge_edge"] = std::move(edge_edge);
  return report;
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

  const auto t = std::chrono::steady_clock::now();
  const MeshFrames frames = load_mesh_frames(o.t0_path, o.t1_path);
  const TriangleMesh& t0 = frames.start;
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();

  CollisionDetector detector(t0.faces, static_cast<int>(t0.vertex_count()), settings);
  const std::vector<Collision>& collisions = detector.detect(t0.vertices, frames.end);
  const DetectionStats& s = detector.stats();
  if (o.json || !o.out.empty()) {
    const Json report = detect_json(o, t0, collisions, s, load_ms);
    if (o.json) print_json(report);
    if (!o.out.empty()) {
      std::ofstream file(o.out);
      if (!file) throw std::runtime_error(o.out + ": cannot open for writing");
      file << report.dump(2) << '\n';
      file.close();  // flushes: a full disk shows here
      if (!file) throw std::runtime_error(o.out + ": write failed");
    }
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
  command->add_flag("--approximate", o->approximate,
                    "Thickness 0 only: report the pairs interval arithmetic leaves undecided as conservative hits "
                    "(toi a lower bound) instead of deciding them exactly");
  add_bvh_option(*command, o->bvh);
  add_filter_option(*command, o->filter);
  add_network_option(*command, o->network, "--model");
  add_json_flag(*command, o->json);
  command->add_option("--out", o->out, "Also write the JSON report (every collision and the stage times) to this file");
  command->callback([o] { run_detect(*o); });
}

}  // namespace clothcd::cli
