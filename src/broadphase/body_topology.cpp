// Body topology: unique edges and primitive owners. Assigning each vertex and edge to exactly one incident triangle is
// how a triangle hierarchy avoids testing a vertex twice (Jin et al., section 3.3.2).
#include "broadphase/body_topology.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

  // The (smaller vertex, larger vertex, face) triples in lexicographic order, so that each run of equal edges starts
  // with its first face: bucketed by the smaller vertex (a counting sort), then each bucket, a vertex's few
  // neighbours, sorted by (larger vertex, face).
  std::vector<int> bucket_start(static_cast<std::size_t>(vertex_count) + 1, 0);
  const auto half_edge = [&](int f, int k) {
    const int a = faces(f, k), b = faces(f, (k + 1) % 3);
    return std::pair<int, int>{std::min(a, b), std::max(a, b)};
  };
  for (int f = 0; f < face_count; ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto [low, high] = half_edge(f, k);
      if (low != high) ++bucket_start[static_cast<std::size_t>(low) + 1];
    }
  }
  for (int v = 0; v < vertex_count; ++v) bucket_start[v + 1] += bucket_start[v];
  std::vector<std::pair<int, int>> by_low(static_cast<std::size_t>(bucket_start.back()));  // (larger vertex, face)
  std::vector<int> filled(bucket_start.begin(), bucket_start.end() - 1);
  for (int f = 0; f < face_count; ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto [low, high] = half_edge(f, k);
      if (low != high) by_low[static_cast<std::size_t>(filled[low]++)] = {high, f};
    }
  }
  topology.edges.reserve(by_low.size());  // about two half-edges per edge
  for (int v = 0; v < vertex_count; ++v) {
    const auto first = by_low.begin() + bucket_start[v], last = by_low.begin() + bucket_start[v + 1];
    std::sort(first, last);
    for (auto h = first; h != last; ++h) {
      if (h != first && h->first == (h - 1)->first) continue;
      topology.edges.push_back(v);
      topology.edges.push_back(h->first);
      topology.edge_owner.push_back(h->second);
    }
  }
  return topology;
}

}  // namespace clothcd::broadphase
