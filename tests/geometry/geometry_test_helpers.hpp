#pragma once
// Helpers of the geometry tests: random meshes, topology checks, real models.

#include <map>
#include <random>
#include <utility>

#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"
#include "support/test_support.hpp"

namespace clothcd::test {

/// `count` points uniformly in [-scale, scale]^3 and `count` random triangles over them (a triangle soup).
inline TriangleMesh random_soup(int count, std::uint64_t seed, double scale = 1.0) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> coordinate(-scale, scale);
  std::uniform_int_distribution<int> index(0, count - 1);
  TriangleMesh mesh;
  mesh.vertices.resize(count, 3);
  for (int i = 0; i < count; ++i) mesh.vertices.row(i) << coordinate(random), coordinate(random), coordinate(random);
  mesh.faces.resize(count, 3);
  for (int f = 0; f < count; ++f) mesh.faces.row(f) << index(random), index(random), index(random);
  return mesh;
}

/// Faces per undirected edge and uses per directed edge.
struct EdgeCounts {
  std::map<std::pair<int, int>, int> undirected;
  std::map<std::pair<int, int>, int> directed;
};

inline EdgeCounts count_edges(const TriangleMesh& mesh) {
  EdgeCounts counts;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      ++counts.undirected[{std::min(a, b), std::max(a, b)}];
      ++counts.directed[{a, b}];
    }
  }
  return counts;
}

/// True when every edge has one or two faces and the faces around every edge are consistently oriented.
inline bool is_oriented_manifold(const TriangleMesh& mesh) {
  const EdgeCounts counts = count_edges(mesh);
  for (const auto& [edge, n] : counts.undirected) {
    if (n > 2) return false;
  }
  for (const auto& [edge, n] : counts.directed) {
    if (n > 1) return false;
  }
  return true;
}

/// A model of the catalog, fetched into the shared test cache.
inline TriangleMesh load_model(const std::string& name) { return load_mesh(fetch_model(name, test_model_dir())); }

}  // namespace clothcd::test
