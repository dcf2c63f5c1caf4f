// `clothcd detect T0_MESH T1_MESH`: continuous collision detection of one step of a deformable mesh against itself
// (the obstacle may be part of the same mesh); prints counts and stage times, writes every collision as JSON.
// `--filter network` runs the detector's network culling (the pair network in front of the combined filters).
#include <array>
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
#include "clothcd/mesh/mesh_frames.hpp"
#include "commands.hpp"

namespace clothcd::cli {
namespace {

struct DetectOptions {
  std::string t0_path;
  std::string t1_path;
  double thickness = 0.0;
  bool exact = false;
  std::string bvh = "sphere-root-aabb";
  std::string filter = "combined";
  std::string model;
  std::string out;
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
std::string milliseconds(double ms) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << ms;
  return text.str();
}

void write_json(std::ostream& out, const DetectOptions& o, const TriangleMesh& mesh,
                const std::vector<Collision>& collisions, const DetectionStats& s, double load_ms) {
  const std::vector<int> faces = collision_faces(mesh, collisions);
  long vf = 0, ee = 0;
  for (const Collision& c : collisions) (c.kind == PairKind::VertexFace ? vf : ee) += 1;
  out << std::setprecision(17);
  out << "{\n  \"t0\": " << json_string(o.t0_path) << ",\n  \"t1\": " << json_string(o.t1_path) << ",\n"
      << "  \"vertices\": " << mesh.vertex_count() << ",\n  \"faces\": " << mesh.face_count() << ",\n"
      << "  \"thickness\": " << o.thickness << ",\n  \"exact\": " << (o.exact ? "true" : "false") << ",\n  \"bvh\": \"" << o.bvh << "\",\n  \"filter\": \"" << o.filter
      << "\",\n  \"counts\": {\"candidates_vertex_face\": " << s.candidates_vertex_face
      << ", \"candidates_edge_edge\": " << s.candidates_edge_edge << ", \"culled\": " << s.culled
      << ", \"vertex_face\": " << vf << ", \"edge_edge\": " << ee << "},\n"
      << "  \"times_ms\": {\"load\": " << milliseconds(load_ms) << ", \"refit\": " << milliseconds(s.refit_ms)
      << ", \"traversal\": " << milliseconds(s.traversal_ms) << ", \"filters\": " << milliseconds(s.culling_ms)
      << ", \"exact\": " << milliseconds(s.exact_ms) << "},\n";
  if (o.filter == "network")
    out << "  \"network\": {\"dropped\": " << s.network_dropped << ", \"overruled\": " << s.network_overruled
        << ", \"kept\": " << s.network_kept << ", \"network_ms\": " << milliseconds(s.network_ms)
        << ", \"filters_ms\": " << milliseconds(s.network_filters_ms) << "},\n";
  const char* separator = "";
  out << "  \"vertex_face\": [";
  std::size_t vertex_face_index = 0;
  for (const Collision& c : collisions) {
    if (c.kind != PairKind::VertexFace) continue;
    const int f = faces[vertex_face_index++];
    out << separator << "\n    {\"pair\": [" << c.vertices[0].vertex << ", " << f << "], \"toi\": " << c.toi
        << (c.conservative ? ", \"conservative\": true" : "") << "}";
    separator = ",";
  }
  out << "\n  ],\n  \"edge_edge\": [";
  separator = "";
  for (const Collision& c : collisions) {
    if (c.kind != PairKind::EdgeEdge) continue;
    out << separator << "\n    {\"pair\": [[" << c.vertices[0].vertex << ", " << c.vertices[1].vertex << "], ["
        << c.vertices[2].vertex << ", " << c.vertices[3].vertex << "]], \"toi\": " << c.toi
        << (c.conservative ? ", \"conservative\": true" : "") << "}";
    separator = ",";
  }
  out << "\n  ]\n}\n";
}

void run_detect(const DetectOptions& o) {
  static const std::map<std::string, HierarchyKind> hierarchies = {
      {"sphere-root-aabb", HierarchyKind::SphereRootAabb}, {"aabb", HierarchyKind::Aabb},
      {"aabb-obb", HierarchyKind::AabbObb}};
  static const std::map<std::string, CullingMode> filters = {{"none", CullingMode::None},
                                                             {"nonpenetration", CullingMode::NonPenetration},
                                                             {"projection", CullingMode::Projection},
                                                             {"combined", CullingMode::Filters},
                                                             {"network", CullingMode::Network}};
  if (o.filter != "network" && !o.model.empty()) throw std::invalid_argument("--model needs --filter network");
  DetectorSettings settings;
  settings.model_path = o.model;
  settings.hierarchy = hierarchies.at(o.bvh);
  settings.culling = filters.at(o.filter);
  settings.thickness = o.thickness;
  settings.decide_exactly = o.exact;

  const auto t = std::chrono::steady_clock::now();
  const MeshFrames frames = load_mesh_frames(o.t0_path, o.t1_path);
  const TriangleMesh& t0 = frames.start;
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();

  CollisionDetector detector(t0.faces, static_cast<int>(t0.vertex_count()), settings);
  const std::vector<Collision>& collisions = detector.detect(t0.vertices, frames.end);
  const DetectionStats& s = detector.stats();
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
  if (o.out.empty()) return;
  std::ofstream file(o.out);
  if (!file) throw std::runtime_error(o.out + ": cannot open for writing");
  write_json(file, o, t0, collisions, s, load_ms);
  file.close();  // flushes: a full disk shows here
  if (!file) throw std::runtime_error(o.out + ": write failed");
  std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void add_detect_command(CLI::App& app) {
  auto* command = app.add_subcommand("detect", "Continuous collision detection between two frames of one mesh");
  auto o = std::make_shared<DetectOptions>();
  command->add_option("T0_MESH", o->t0_path, "Mesh at the start of the step")->required();
  command->add_option("T1_MESH", o->t1_path, "Same mesh (same faces) at the end of the step")->required();
  command->add_option("--thickness", o->thickness, "Minimum separation, in mesh units")
      ->check(finite_number(0.0, std::numeric_limits<double>::infinity()));
  command->add_flag("--exact", o->exact,
                    "Thickness 0: decide the pairs interval arithmetic leaves undecided exactly instead of reporting "
                    "them as conservative hits");
  command->add_option("--bvh", o->bvh, "Hierarchy")
      ->check(CLI::IsMember({"sphere-root-aabb", "aabb", "aabb-obb"}))
      ->capture_default_str();
  command->add_option("--filter", o->filter, "Culling before the exact test")
      ->check(CLI::IsMember({"none", "nonpenetration", "projection", "combined", "network"}))
      ->capture_default_str();
  command->add_option("--model", o->model,
                      "Pair network for --filter network: model directory or network.xml (default models/default)");
  command->add_option("--out", o->out, "Write every collision and the stage times as JSON");
  command->callback([o] { run_detect(*o); });
}

}  // namespace clothcd::cli
