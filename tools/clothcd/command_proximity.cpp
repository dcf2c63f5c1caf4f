// `clothcd proximity MESH --distance D`: the pairs of one state of a mesh (one body with self-collision) closer than
// D (CollisionDetector::proximity), each with its distance, closest points, direction and where the closest points
// lie; prints counts and stage times, or with --json (and into --out) every pair, written one pair at a time.
// `--contacts` adds the closest-feature contacts of those pairs (a barrier's active set); `--minimum` answers the
// other question instead: the smallest distance and a pair that has it (CollisionDetector::minimum_distance), with
// --distance, when given, as the upper bound of the search.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "face_names.hpp"
#include "json_stream.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"
#include "state_json.hpp"

namespace clothcd::cli {
namespace {

struct ProximityOptions {
  std::string mesh_path;
  double distance = std::numeric_limits<double>::infinity();
  std::string bvh = "sphere-root-aabb";
  std::string out;
  bool json = false;
  bool minimum = false;
  bool contacts = false;
  long max_collisions = DetectorSettings{}.max_collisions;
};

// The report's fields before the pairs.
Json proximity_json_head(const ProximityOptions& o, const TriangleMesh& mesh, const DetectionStats& s,
                         double load_ms) {
  Json report = json_report("proximity");
  report["mesh"] = o.mesh_path;
  report["vertices"] = mesh.vertex_count();
  report["faces"] = mesh.face_count();
  report["distance"] = std::isfinite(o.distance) ? Json(o.distance) : Json(nullptr);
  report["bvh"] = o.bvh;
  report["counts"] = {{"candidates_vertex_face", s.candidates_vertex_face},
                      {"candidates_edge_edge", s.candidates_edge_edge}};
  report["times_ms"] = state_times_json(load_ms, s);
  return report;
}

// A pair as one line of the text report.
std::string pair_text(const Proximity& p) {
  const auto& v = p.vertices;
  std::ostringstream text;
  if (p.kind == PairKind::VertexFace) {
    text << "vertex " << v[0].vertex << " against face (" << v[1].vertex << ", " << v[2].vertex << ", " << v[3].vertex
         << ")";
  } else {
    text << "edge (" << v[0].vertex << ", " << v[1].vertex << ") against edge (" << v[2].vertex << ", " << v[3].vertex
         << ")";
  }
  return text.str() + ", " + distance_type_name(p.type);
}

// --minimum: the smallest distance and its pair.
void report_minimum(const ProximityOptions& o, CollisionDetector& detector, const TriangleMesh& mesh,
                    double load_ms) {
  const MinimumDistance m = detector.minimum_distance(mesh.vertices, o.distance);
  const DetectionStats& s = detector.stats();
  if (o.json || !o.out.empty()) {
    Json report = proximity_json_head(o, mesh, s, load_ms);
    FaceNames faces(mesh);
    const int face = m.found && m.pair.kind == PairKind::VertexFace ? faces.next(m.pair.vertices) : -1;
    report["minimum"] = {{"found", m.found},
                         {"distance", std::isfinite(m.distance) ? Json(m.distance) : Json(nullptr)},
                         {"pair", m.found ? proximity_json(m.pair, face) : Json(nullptr)}};
    write_to(o.json, o.out, [&](std::ostream& out) { out << report.dump(2) << '\n'; });
    if (o.json) return;
  }
  std::cout << "mesh:        " << mesh.vertex_count() << " vertices, " << mesh.faces.rows() << " faces (one body "
            << "with self-collision)\n"
            << "candidates:  " << s.candidates_vertex_face << " vertex-face, " << s.candidates_edge_edge
            << " edge-edge (" << o.bvh << ")\n"
            << std::setprecision(17) << "minimum:     ";
  if (m.found) {
    std::cout << "distance " << m.distance << ", " << pair_text(m.pair) << '\n';
  } else {
    std::cout << "no pair closer than " << o.distance << '\n';
  }
  std::cout << std::fixed << std::setprecision(3) << "times (ms):  load " << load_ms << ", build+refit " << s.refit_ms
            << ", traversal " << s.traversal_ms << ", exact " << s.exact_ms << '\n';
  if (!o.out.empty()) std::cout << "wrote " << o.out << '\n';
}

// Writes the report: the head, the "vertex_face" and "edge_edge" arrays and, with --contacts, "contacts".
void write_proximity_json(std::ostream& out, const Json& head, const TriangleMesh& mesh,
                          const std::vector<Proximity>& pairs, const std::vector<FeatureContact>* contacts) {
  JsonStream stream(out, head);
  FaceNames faces(mesh);
  for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
    stream.array(kind == PairKind::VertexFace ? "vertex_face" : "edge_edge", [&](const auto& write) {
      for (const Proximity& p : pairs) {
        if (p.kind == kind) write(proximity_json(p, kind == PairKind::VertexFace ? faces.next(p.vertices) : -1));
      }
    });
  }
  if (contacts != nullptr) {
    stream.array("contacts", [&](const auto& write) {
      for (const FeatureContact& c : *contacts) write(contact_json(c));
    });
  }
  stream.close();
}

void run_proximity(const ProximityOptions& o) {
  if (!o.minimum && !std::isfinite(o.distance)) throw std::invalid_argument("proximity: --distance is required");
  if (o.minimum && o.contacts) throw std::invalid_argument("proximity: --contacts goes without --minimum");
  if (!o.out.empty()) check_output_file(o.out, "--out");
  double load_ms = 0.0;
  const TriangleMesh mesh = load_state_mesh(o.mesh_path, load_ms);
  CollisionDetector detector = state_detector(mesh, o.bvh, o.max_collisions);
  if (o.minimum) {
    report_minimum(o, detector, mesh, load_ms);
    return;
  }
  const std::vector<Proximity>& pairs = detector.proximity(mesh.vertices, o.distance);
  const DetectionStats& s = detector.stats();
  std::vector<FeatureContact> contacts;
  if (o.contacts) contacts = closest_feature_contacts(pairs);
  long vf = 0;
  for (const Proximity& p : pairs) vf += p.kind == PairKind::VertexFace ? 1 : 0;
  if (o.json || !o.out.empty()) {
    Json head = proximity_json_head(o, mesh, s, load_ms);
    head["counts"]["vertex_face"] = vf;
    head["counts"]["edge_edge"] = pairs.size() - static_cast<std::size_t>(vf);
    if (o.contacts) head["counts"]["contacts"] = contacts.size();
    write_to(o.json, o.out, [&](std::ostream& out) {
      write_proximity_json(out, head, mesh, pairs, o.contacts ? &contacts : nullptr);
    });
    if (o.json) return;
  }
  std::cout << "mesh:        " << mesh.vertex_count() << " vertices, " << mesh.faces.rows() << " faces (one body "
            << "with self-collision)\n"
            << "candidates:  " << s.candidates_vertex_face << " vertex-face, " << s.candidates_edge_edge
            << " edge-edge (" << o.bvh << ")\n"
            << "within " << o.distance << ": " << vf << " vertex-face, " << pairs.size() - static_cast<std::size_t>(vf)
            << " edge-edge\n";
  if (o.contacts) std::cout << "contacts:    " << contacts.size() << " closest-feature pairs\n";
  std::cout << std::fixed << std::setprecision(3) << "times (ms):  load " << load_ms << ", build+refit " << s.refit_ms
            << ", traversal " << s.traversal_ms << ", exact " << s.exact_ms << '\n';
  if (!o.out.empty()) std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void add_proximity_command(CLI::App& app) {
  auto* command =
      app.add_subcommand("proximity", "Pairs of one mesh closer than a distance, or its smallest pair distance");
  auto o = std::make_shared<ProximityOptions>();
  command->add_option("MESH", o->mesh_path, "The mesh (one body, against itself)")->required();
  command->add_option("--distance", o->distance,
                      "Report the pairs closer than this (mesh units); with --minimum, the search's upper bound")
      ->check(finite_number(0.0, std::numeric_limits<double>::infinity(), true));
  add_bvh_option(*command, o->bvh);
  add_json_flag(*command, o->json);
  command->add_option("--out", o->out, "Also write the JSON report (every pair and the stage times) to this file");
  command->add_option("--max-collisions", o->max_collisions,
                      "Pair budget: more pairs within the distance stop the search with an error (exit code 1)")
      ->check(CLI::Range(1L, kLargestCollisionBudget));
  command->add_flag("--minimum", o->minimum,
                    "Report the smallest pair distance and a pair that has it, instead of every pair within --distance");
  command->add_flag("--contacts", o->contacts,
                    "Also report the closest-feature contacts of the pairs (each once: a barrier's active set)");
  command->callback([o] { run_proximity(*o); });
}

}  // namespace clothcd::cli
