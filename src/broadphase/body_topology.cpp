// Body topology: unique edges and primitive owners. Assigning each vertex and edge to exactly one incident triangle is
// how a triangle hierarchy avoids testing a vertex twice (Jin et al., section 3.3.2).
#include "clothcd/broadphase/body_topology.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace clothcd::broadphase {
namespace {

void check_faces(const Faces& faces, int vertex_count) {
  if (vertex_count < 1) throw std::invalid_argument("body topology: the body has no vertex");
  if (faces.rows() == 0) throw std::invalid_argument("body topology: the body has no face");
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= vertex_count) {
        throw std::invalid_argument("body topology: face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                                    ", outside [0, " + std::to_string(vertex_count) + ")");
      }
    }
  }
}

}  // namespace

BodyTopology build_body_topology(const Faces& faces, int vertex_count) {
  check_faces(faces, vertex_count);
  BodyTopology topology;
  topology.vertex_count = vertex_count;
  topology.faces = faces;
  const int face_count = static_cast<int>(faces.rows());

  topology.vertex_owner.assign(vertex_count, -1);
  for (int f = face_count - 1; f >= 0; --f) {
    for (int k = 0; k < 3; ++k) topology.vertex_owner[faces(f, k)] = f;
  }

  // (smaller vertex, larger vertex, face) triples sorted: each run of equal edges starts with its first face.
  std::vector<std::array<int, 3>> half_edges;
  half_edges.reserve(3 * static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a != b) half_edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  std::sort(half_edges.begin(), half_edges.end());
  for (std::size_t i = 0; i < half_edges.size(); ++i) {
    if (i > 0 && half_edges[i][0] == half_edges[i - 1][0] && half_edges[i][1] == half_edges[i - 1][1]) continue;
    topology.edges.push_back(half_edges[i][0]);
    topology.edges.push_back(half_edges[i][1]);
    topology.edge_owner.push_back(half_edges[i][2]);
  }
  return topology;
}

}  // namespace clothcd::broadphase
