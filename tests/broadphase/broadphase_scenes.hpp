#pragma once
// Test scenes for the broad phase: a cloth grid over an obstacle with seeded random motion, random triangle soups; and
// the reference of the searches restricted to moved vertices.

#include <cstdint>
#include <random>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/swept_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::test {

/// One body with its step data: topology, positions at t0/t1, swept boxes and a hierarchy.
struct TestBody {
  broadphase::BodyTopology topology;
  Vertices start;
  Vertices end;
  broadphase::SweptBoxes boxes;
  broadphase::Bvh bvh;

  TestBody(const TriangleMesh& mesh, const Vertices& moved_end, double thickness, broadphase::BvhSettings settings)
      : topology(broadphase::build_body_topology(mesh.faces, static_cast<int>(mesh.vertex_count()))),
        start(mesh.vertices),
        end(moved_end),
        bvh(settings) {
    broadphase::compute_swept_boxes(topology, start, end, thickness, boxes);
    bvh.build(topology, boxes, start, end);
  }

  broadphase::BodyView view(int body) const { return {body, &topology, &boxes, &bvh}; }
};

/// `positions` plus a seeded random displacement of up to `amplitude` per coordinate.
inline Vertices jitter(const Vertices& positions, double amplitude, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Vertices out = positions;
  for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] += u(rng);
  return out;
}

/// A random triangle soup: `vertex_count` points in the unit cube, `face_count` faces of random vertices (some faces
/// repeat an index, i.e. are degenerate, on purpose).
inline TriangleMesh random_soup(int vertex_count, int face_count, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, vertex_count - 1);
  TriangleMesh mesh;
  mesh.vertices.resize(vertex_count, 3);
  for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) mesh.vertices.data()[i] = u(rng);
  mesh.faces.resize(face_count, 3);
  for (int f = 0; f < face_count; ++f) {
    for (int k = 0; k < 3; ++k) mesh.faces(f, k) = pick(rng);
  }
  return mesh;
}

/// The pairs of `all` with a moved vertex of body `body` (flags per vertex): the reference for searches restricted to
/// moved vertices, from the unrestricted brute-force pairs.
inline broadphase::CandidateSet pairs_touching_moved(const broadphase::CandidateSet& all, int body,
                                                     const broadphase::BodyTopology& topology,
                                                     const std::vector<std::uint8_t>& moved) {
  auto face_moved = [&](int f) {
    return moved[topology.faces(f, 0)] || moved[topology.faces(f, 1)] || moved[topology.faces(f, 2)];
  };
  auto edge_moved = [&](int e) { return moved[topology.edges[2 * e]] || moved[topology.edges[2 * e + 1]]; };
  broadphase::CandidateSet out;
  for (const broadphase::VertexFaceCandidate& c : all.vertex_face) {
    if ((c.vertex_body == body && moved[c.vertex]) || (c.face_body == body && face_moved(c.face))) {
      out.vertex_face.push_back(c);
    }
  }
  for (const broadphase::EdgeEdgeCandidate& c : all.edge_edge) {
    if ((c.body_a == body && edge_moved(c.edge_a)) || (c.body_b == body && edge_moved(c.edge_b))) {
      out.edge_edge.push_back(c);
    }
  }
  return out;
}

}  // namespace clothcd::test
