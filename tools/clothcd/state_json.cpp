// The state queries' records as JSON (state_json.hpp).
#include "state_json.hpp"

#include <array>
#include <chrono>

#include "clothcd/mesh/mesh_io.hpp"
#include "json_stream.hpp"

namespace clothcd::cli {
namespace {

constexpr std::array<const char*, 16> kDistanceTypeNames{
    "point_face",          "point_edge0",         "point_edge1",         "point_edge2",
    "point_vertex0",       "point_vertex1",       "point_vertex2",       "edge_edge",
    "edge_vertex_b0",      "edge_vertex_b1",      "vertex_a0_edge",      "vertex_a1_edge",
    "vertex_a0_vertex_b0", "vertex_a0_vertex_b1", "vertex_a1_vertex_b0", "vertex_a1_vertex_b1"};

constexpr std::array<const char*, 4> kContactKindNames{"vertex_vertex", "vertex_edge", "edge_edge", "vertex_face"};

// Vertices of each contact kind, as ContactKind lists them.
constexpr std::array<std::size_t, 4> kContactVertexCount{2, 3, 4, 4};

}  // namespace

TriangleMesh load_state_mesh(const std::string& path, double& load_ms) {
  const auto start = std::chrono::steady_clock::now();
  LoadOptions options;
  options.join_identical_vertices = false;
  options.drop_degenerate_faces = false;
  TriangleMesh mesh = load_mesh(path, options);
  load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return mesh;
}

CollisionDetector state_detector(const TriangleMesh& mesh, const std::string& bvh, long max_collisions) {
  DetectorSettings settings;
  settings.hierarchy = hierarchy_named(bvh);
  settings.max_collisions = max_collisions;
  return CollisionDetector(mesh.faces, static_cast<int>(mesh.vertex_count()), settings);
}

const char* distance_type_name(DistanceType type) { return kDistanceTypeNames[static_cast<std::size_t>(type)]; }

Json proximity_json(const Proximity& p, int face) {
  Json item;
  const auto& v = p.vertices;
  if (p.kind == PairKind::VertexFace) {
    item["pair"] = {v[0].vertex, face};
    item["face_vertices"] = {v[1].vertex, v[2].vertex, v[3].vertex};
    item["barycentric"] = {1.0 - p.parameters[0] - p.parameters[1], p.parameters[0], p.parameters[1]};
  } else {
    item["pair"] = {{v[0].vertex, v[1].vertex}, {v[2].vertex, v[3].vertex}};
    item["edge_parameters"] = {p.parameters[0], p.parameters[1]};
  }
  item["bodies"] = {v[0].body, v[1].body, v[2].body, v[3].body};
  item["distance"] = p.distance;
  item["direction"] = json_vector(p.direction);
  item["type"] = distance_type_name(p.type);
  return item;
}

Json contact_json(const FeatureContact& c) {
  const auto kind = static_cast<std::size_t>(c.kind);
  Json vertices = Json::array(), bodies = Json::array();
  for (std::size_t k = 0; k < kContactVertexCount[kind]; ++k) {
    vertices.push_back(c.vertices[k].vertex);
    bodies.push_back(c.vertices[k].body);
  }
  return {{"kind", kContactKindNames[kind]}, {"vertices", vertices}, {"bodies", bodies}, {"distance", c.distance}};
}

Json intersection_json(const FaceIntersection& x) {
  return {{"faces", {x.faces[0], x.faces[1]}},
          {"bodies", {x.bodies[0], x.bodies[1]}},
          {"edge_face", x.edge_face},
          {"edge", {x.edge[0].vertex, x.edge[1].vertex}},
          {"edge_parameter", x.edge_parameter},
          {"face_weights", {x.face_weights[0], x.face_weights[1]}},
          {"coplanar", x.coplanar}};
}

Json state_times_json(double load_ms, const DetectionStats& s) {
  return {{"load", milliseconds(load_ms)},
          {"refit", milliseconds(s.refit_ms)},
          {"traversal", milliseconds(s.traversal_ms)},
          {"exact", milliseconds(s.exact_ms)}};
}

}  // namespace clothcd::cli
