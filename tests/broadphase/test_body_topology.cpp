// Body topology: unique edges, exactly one owner per vertex and edge, index validation.
#include <catch2/catch.hpp>

#include <set>
#include <utility>

#include "clothcd/broadphase/body_topology.hpp"
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
