// Body topology: unique edges, exactly one owner per vertex and edge, index validation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using clothcd::broadphase::build_body_topology;

TEST_CASE("a grid has the expected unique edges and owners", "[broadphase][topology]") {
  const int columns = 5, rows = 4;
  const clothcd::TriangleMesh grid = clothcd::make_grid(columns, rows);
  const auto topology = build_body_topology(grid.faces, static_cast<int>(grid.vertex_count()));
  // Horizontal + vertical + one diagonal per quad.
  CHECK(topology.edge_count() == (columns - 1) * rows + columns * (rows - 1) + (columns - 1) * (rows - 1));
  std::set<std::pair<int, int>> unique;
  for (int e = 0; e < topology.edge_count(); ++e) {
    const int a = topology.edges[2 * e], b = topology.edges[2 * e + 1];
    CHECK(a < b);
    unique.insert({a, b});
    const int owner = topology.edge_owner[e];
    CHECK((topology.face_has_vertex(owner, a) && topology.face_has_vertex(owner, b)));
  }
  CHECK(unique.size() == static_cast<std::size_t>(topology.edge_count()));
  for (int v = 0; v < topology.vertex_count; ++v) {
    REQUIRE(topology.vertex_owner[v] >= 0);
    CHECK(topology.face_has_vertex(topology.vertex_owner[v], v));
  }
}

TEST_CASE("unused vertices have no owner and degenerate edges are left out", "[broadphase][topology]") {
  clothcd::Faces faces(2, 3);
  faces << 0, 1, 2, 2, 2, 3;  // the second face is degenerate: edge (2, 2) must not appear
  const auto topology = build_body_topology(faces, 5);
  CHECK(topology.edge_count() == 4);  // 01 12 02 23
  CHECK(topology.vertex_owner[4] == -1);
  CHECK(topology.vertex_owner[3] == 1);
}

TEST_CASE("bad topology is rejected", "[broadphase][topology]") {
  clothcd::Faces faces(1, 3);
  faces << 0, 1, 3;
  CHECK_THROWS_AS(build_body_topology(faces, 3), std::invalid_argument);
  faces << 0, -1, 2;
  CHECK_THROWS_AS(build_body_topology(faces, 3), std::invalid_argument);
  CHECK_THROWS_AS(build_body_topology(clothcd::Faces(0, 3), 3), std::invalid_argument);
}

namespace {

// The edges and owners by the plain definition: every half-edge (smaller vertex, larger vertex, face) of a face with
// two different ends, sorted; the first of each run of equal edges.
void reference_edges(const clothcd::Faces& faces, std::vector<int>& edges, std::vector<int>& owners) {
  std::vector<std::array<int, 3>> half_edges;
  for (int f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a != b) half_edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  std::sort(half_edges.begin(), half_edges.end());
  for (std::size_t i = 0; i < half_edges.size(); ++i) {
    if (i > 0 && half_edges[i][0] == half_edges[i - 1][0] && half_edges[i][1] == half_edges[i - 1][1]) continue;
    edges.push_back(half_edges[i][0]);
    edges.push_back(half_edges[i][1]);
    owners.push_back(half_edges[i][2]);
  }
}

}  // namespace

TEST_CASE("edges and owners equal a sort of every half-edge, on random and degenerate faces",
          "[broadphase][topology][random]") {
  std::mt19937 random(20261129);
  for (int trial = 0; trial < 200; ++trial) {
    // Few vertices make repeated, non-manifold and degenerate faces common; a fan makes one vertex's bucket large.
    const int vertex_count = 1 + static_cast<int>(random() % (trial < 100 ? 12 : 400));
    const int face_count = 1 + static_cast<int>(random() % 300);
    const bool fan = trial % 4 == 3;
    std::uniform_int_distribution<int> vertex(0, vertex_count - 1);
    clothcd::Faces faces(face_count, 3);
    for (int f = 0; f < face_count; ++f) {
      for (int k = 0; k < 3; ++k) faces(f, k) = fan && k == 0 ? 0 : vertex(random);
    }
    std::vector<int> edges, owners;
    reference_edges(faces, edges, owners);
    const auto topology = build_body_topology(faces, vertex_count);
    CHECK(topology.edges == edges);
    CHECK(topology.edge_owner == owners);
  }
}
