#pragma once
// The records of the detector's state queries as the JSON reports of `clothcd proximity` and `clothcd intersections`
// give them (docs/json.md), and the mesh they read.

#include <string>

#include "clothcd/detection/collision_detector.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {

/// The mesh of a state query, read as `detect` reads a frame (every vertex and face kept as stored); `load_ms` is set
/// to the time it took.
[[nodiscard]] TriangleMesh load_state_mesh(const std::string& path, double& load_ms);

/// A detector for the mesh as one body with self-collision, with the hierarchy of --bvh and the collision budget.
[[nodiscard]] CollisionDetector state_detector(const TriangleMesh& mesh, const std::string& bvh, long max_collisions);

/// The name of a DistanceType, as the reports give it ("point_face", "edge_vertex_b0", ...).
[[nodiscard]] const char* distance_type_name(DistanceType type);

/// One pair within the distance: pair (vertex and face index, or two edges), face_vertices and barycentric
/// (vertex-face) or edge_parameters (edge-edge), bodies, distance, direction and type. `face` is the face's index
/// (vertex-face pairs).
[[nodiscard]] Json proximity_json(const Proximity& p, int face);

/// One closest-feature contact: kind ("vertex_vertex", ...), vertices (the ones its kind uses), bodies, distance.
[[nodiscard]] Json contact_json(const FeatureContact& c);

/// One intersecting face pair: faces, bodies, edge_face, edge, edge_parameter, face_weights, coplanar.
[[nodiscard]] Json intersection_json(const FaceIntersection& x);

/// The reports' stage times: load, refit, traversal, exact.
[[nodiscard]] Json state_times_json(double load_ms, const DetectionStats& s);

}  // namespace clothcd::cli
