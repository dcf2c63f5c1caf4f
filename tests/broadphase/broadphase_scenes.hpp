#pragma once
// Test scenes for the broad phase: a cloth grid over an obstacle with seeded random motion, random triangle soups; and
// the reference of the searches restricted to moved vertices.

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/swept_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
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

/// An n x n grid of side 2.4 bent over a unit sphere at the origin, so that it folds near itself and touches the
/// sphere.
inline TriangleMesh draped_cloth(int n) {
  TriangleMesh cloth = make_grid(n, n, 2.4, 2.4);
  for (Eigen::Index v = 0; v < cloth.vertex_count(); ++v) {
    const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2);
    cloth.vertices(v, 1) = 1.02 - 0.5 * (x * x + z * z);
  }
  return cloth;
}

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

/// `count` separate small triangles (corners within `size` of a random point in the unit cube, three vertices each):
/// their boxes rarely overlap, so their pairs have positive gaps.
inline TriangleMesh scattered_triangles(int count, double size, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0), d(-size, size);
  TriangleMesh mesh;
  mesh.vertices.resize(3 * count, 3);
  mesh.faces.resize(count, 3);
  for (int f = 0; f < count; ++f) {
    const double c[3] = {u(rng), u(rng), u(rng)};
    for (int k = 0; k < 3; ++k) {
      mesh.faces(f, k) = 3 * f + k;
      for (int axis = 0; axis < 3; ++axis) mesh.vertices(3 * f + k, axis) = c[axis] + d(rng);
    }
  }
  return mesh;
}

/// The largest of the six per-axis differences between the bounds of two boxes, rounded (negative when they overlap
/// with room): the smallest gap bound within which the searches take the boxes (the test of gap_bound.hpp passes
/// exactly when this is at most the bound).
inline double box_gap(const broadphase::FlatBox& a, const broadphase::FlatBox& b) {
  double gap = a.min[0] - b.max[0];
  for (int k = 0; k < 3; ++k) gap = std::max({gap, a.min[k] - b.max[k], b.min[k] - a.max[k]});
  return gap;
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
