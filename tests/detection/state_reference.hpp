#pragma once
// Brute-force references of the questions of one state, for the detector's tests: every pair detect() covers,
// checked one by one in exact arithmetic (GMP rationals), with no hierarchy and no filter.
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <tuple>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "clothcd/detection/face_intersection.hpp"
#include "clothcd/detection/proximity.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"
#include "geometry/exact_pair_distance.hpp"
#include "geometry/exact_triangle_intersection.hpp"
#include "geometry/triangle_intersection.hpp"

namespace clothcd::test {

/// One body of a state: its mesh at the state's positions (body 0 is the cloth).
struct StateBody {
  broadphase::BodyTopology topology;  ///< Faces and edges, as the detector numbers them.
  Vertices positions;                 ///< Positions at the state.
};

/// The bodies of a state: the cloth and the obstacles.
inline std::vector<StateBody> state_bodies(const TriangleMesh& cloth, const Vertices& cloth_positions,
                                           const std::vector<TriangleMesh>& obstacles) {
  std::vector<StateBody> bodies;
  bodies.push_back({broadphase::build_body_topology(cloth.faces, static_cast<int>(cloth.vertex_count())),
                    cloth_positions});
  for (const TriangleMesh& o : obstacles) {
    bodies.push_back({broadphase::build_body_topology(o.faces, static_cast<int>(o.vertex_count())), o.vertices});
  }
  return bodies;
}

/// A pair of the reference: its kind, vertices and exact squared distance.
struct ReferencePair {
  PairKind kind = PairKind::VertexFace;  ///< Kind.
  std::array<VertexRef, 4> vertices{};   ///< As Proximity orders them.
  mpq_class squared_distance;            ///< Exact.
  DistanceType type = DistanceType::PointFace;  ///< Exact.
};

/// The vertices of a pair as a comparable tuple.
inline std::array<std::int64_t, 9> pair_id(PairKind kind, const std::array<VertexRef, 4>& v) {
  std::array<std::int64_t, 9> id{static_cast<std::int64_t>(kind)};
  for (int k = 0; k < 4; ++k) {
    id[1 + 2 * k] = v[k].body;
    id[2 + 2 * k] = v[k].vertex;
  }
  return id;
}

/// Calls `visit(ReferencePair)` for every pair detect() covers at the state: vertex-face and edge-edge pairs of the
/// cloth sharing no vertex, and of the cloth against each obstacle (both ways for vertex-face).
template <class Visit>
void for_each_reference_pair(const std::vector<StateBody>& bodies, const Visit& visit) {
  const auto point = [&](int body, int vertex) -> Eigen::Vector3d {
    return bodies[static_cast<std::size_t>(body)].positions.row(vertex).transpose();
  };
  const auto vertex_face = [&](int vb, int v, int fb, int f) {
    const Faces& faces = bodies[static_cast<std::size_t>(fb)].topology.faces;
    if (vb == fb && (faces(f, 0) == v || faces(f, 1) == v || faces(f, 2) == v)) return;
    ReferencePair p;
    p.kind = PairKind::VertexFace;
    p.vertices = {VertexRef{vb, v}, VertexRef{fb, faces(f, 0)}, VertexRef{fb, faces(f, 1)}, VertexRef{fb, faces(f, 2)}};
    const geometry::ExactPairDistance d = geometry::exact_point_triangle_distance(
        point(vb, v), point(fb, faces(f, 0)), point(fb, faces(f, 1)), point(fb, faces(f, 2)));
    p.squared_distance = d.squared_distance;
    p.type = d.type;
    visit(p);
  };
  const auto edge_edge = [&](int ba, int ea, int bb, int eb) {
    const std::vector<int>& a = bodies[static_cast<std::size_t>(ba)].topology.edges;
    const std::vector<int>& b = bodies[static_cast<std::size_t>(bb)].topology.edges;
    const int a0 = a[2 * ea], a1 = a[2 * ea + 1], b0 = b[2 * eb], b1 = b[2 * eb + 1];
    if (ba == bb && (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1)) return;
    ReferencePair p;
    p.kind = PairKind::EdgeEdge;
    p.vertices = {VertexRef{ba, a0}, VertexRef{ba, a1}, VertexRef{bb, b0}, VertexRef{bb, b1}};
    const geometry::ExactPairDistance d =
        geometry::exact_segment_segment_distance(point(ba, a0), point(ba, a1), point(bb, b0), point(bb, b1));
    p.squared_distance = d.squared_distance;
    p.type = d.type;
    visit(p);
  };
  const int body_count = static_cast<int>(bodies.size());
  const auto used = [&](int body) {
    std::vector<char> in_face(static_cast<std::size_t>(bodies[static_cast<std::size_t>(body)].topology.vertex_count));
    const Faces& faces = bodies[static_cast<std::size_t>(body)].topology.faces;
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) in_face[static_cast<std::size_t>(faces(f, k))] = 1;
    return in_face;
  };
  for (int other = 0; other < body_count; ++other) {
    const StateBody& c = bodies[0];
    const StateBody& o = bodies[static_cast<std::size_t>(other)];
    const std::vector<char> cloth_used = used(0), other_used = used(other);
    for (int v = 0; v < c.topology.vertex_count; ++v) {
      if (!cloth_used[static_cast<std::size_t>(v)]) continue;
      for (int f = 0; f < o.topology.face_count(); ++f) vertex_face(0, v, other, f);
    }
    if (other > 0) {
      for (int v = 0; v < o.topology.vertex_count; ++v) {
        if (!other_used[static_cast<std::size_t>(v)]) continue;
        for (int f = 0; f < c.topology.face_count(); ++f) vertex_face(other, v, 0, f);
      }
    }
    for (int ea = 0; ea < c.topology.edge_count(); ++ea) {
      for (int eb = other == 0 ? ea + 1 : 0; eb < o.topology.edge_count(); ++eb) edge_edge(0, ea, other, eb);
    }
  }
}

/// The pairs within `distance` at the state, by brute force: exact squared distance below distance^2.
inline std::vector<ReferencePair> reference_proximity(const std::vector<StateBody>& bodies, double distance) {
  const mpq_class limit = mpq_class(distance) * mpq_class(distance);
  std::vector<ReferencePair> within;
  for_each_reference_pair(bodies, [&](const ReferencePair& p) {
    if (p.squared_distance < limit) within.push_back(p);
  });
  return within;
}

/// The intersecting face pairs at the state, by brute force (the rational reference of every face pair), sorted as
/// (body, face) of the first face, then of the second.
inline std::vector<std::array<std::int32_t, 4>> reference_intersections(const std::vector<StateBody>& bodies) {
  std::vector<std::array<std::int32_t, 4>> found;
  const auto corners = [&](int body, int face) {
    const StateBody& b = bodies[static_cast<std::size_t>(body)];
    geometry::Triangle t;
    for (int k = 0; k < 3; ++k) t[k] = b.positions.row(b.topology.faces(face, k)).transpose();
    return t;
  };
  const auto indices = [&](int body, int face) {
    const Faces& f = bodies[static_cast<std::size_t>(body)].topology.faces;
    return std::array<int, 3>{f(face, 0), f(face, 1), f(face, 2)};
  };
  const int cloth_faces = bodies[0].topology.face_count();
  for (int other = 0; other < static_cast<int>(bodies.size()); ++other) {
    const int other_faces = bodies[static_cast<std::size_t>(other)].topology.face_count();
    for (int fa = 0; fa < cloth_faces; ++fa) {
      for (int fb = other == 0 ? fa + 1 : 0; fb < other_faces; ++fb) {
        const geometry::SharedCorners shared =
            other == 0 ? geometry::shared_corners(indices(0, fa), indices(0, fb)) : geometry::SharedCorners{};
        if (geometry::exact_intersect_triangles(corners(0, fa), corners(other, fb), shared).intersect) {
          found.push_back({0, fa, other, fb});
        }
      }
    }
  }
  std::sort(found.begin(), found.end());  // the detector's order: first face, then second (body, face)
  return found;
}

}  // namespace clothcd::test
