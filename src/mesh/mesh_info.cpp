// Mesh summary: counts, bounding box, face components (union-find), edge manifoldness and watertightness.
#include "clothcd/mesh/mesh_info.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "clothcd/mesh/mesh_validation.hpp"

namespace clothcd {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

/// Counts, per undirected edge, its uses in each direction.
struct EdgeUse {
  int forward = 0;   // as (min, max)
  int backward = 0;  // as (max, min)
};

}  // namespace

MeshInfo compute_mesh_info(const TriangleMesh& mesh) {
  MeshInfo info;
  info.vertices = mesh.vertex_count();
  info.faces = mesh.face_count();
  if (mesh.vertex_count() > 0) {
    info.bbox_min = mesh.vertices.colwise().minCoeff().transpose();
    info.bbox_max = mesh.vertices.colwise().maxCoeff().transpose();
  }

  UnionFind components(static_cast<std::size_t>(mesh.vertex_count()));
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(static_cast<std::size_t>(3 * mesh.face_count()));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    info.surface_area += 0.5 * (b - a).cross(c - a).norm();
    if (is_degenerate_face(mesh, f)) ++info.degenerate_faces;
    for (int k = 0; k < 3; ++k) {
      const int from = mesh.faces(f, k), to = mesh.faces(f, (k + 1) % 3);
      components.unite(from, to);
      const auto lo = static_cast<std::uint64_t>(std::min(from, to)), hi = static_cast<std::uint64_t>(std::max(from, to));
      EdgeUse& use = edges[lo << 32 | hi];
      (from < to ? use.forward : use.backward)++;
    }
  }
  std::vector<bool> root_seen(static_cast<std::size_t>(mesh.vertex_count()), false);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const int root = components.find(mesh.faces(f, 0));
    if (!root_seen[static_cast<std::size_t>(root)]) {
      root_seen[static_cast<std::size_t>(root)] = true;
      ++info.components;
    }
  }
  bool consistently_paired = true;
  for (const auto& [key, use] : edges) {
    const int total = use.forward + use.backward;
    if (total == 1) ++info.boundary_edges;
    if (total > 2) ++info.non_manifold_edges;
    if (use.forward != 1 || use.backward != 1) consistently_paired = false;
  }
  info.watertight = consistently_paired && !edges.empty();
  return info;
}

}  // namespace clothcd
