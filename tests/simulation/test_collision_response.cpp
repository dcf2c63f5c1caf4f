// Collision response on hand-made pairs: impulses restore the thickness, friction slows sliding, the fail-safe freezes
// or carries vertices, and conservative reports are dropped only when a distance bound proves them apart.
#include <catch2/catch.hpp>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/simulation/collision_response.hpp"
#include "clothcd/simulation/contact_memory.hpp"

using namespace clothcd;
using namespace clothcd::simulation;

namespace {

/// A one-triangle cloth (vertices 0..2) above a big static ground triangle (obstacle body 1), and a fourth free cloth
/// vertex 3 used as the colliding point.
struct Fixture {
  ClothModel model;
  std::vector<Obstacle> obstacles;
  std::vector<Vertices> obstacle_start, obstacle_end;
  Vertices start;

  Fixture() {
    TriangleMesh cloth;
    cloth.vertices.resize(4, 3);
    cloth.vertices << 0, 1, 0, 1, 1, 0, 0, 1, 1, 0.2, 0.01, 0.2;
    cloth.faces.resize(1, 3);
    cloth.faces << 0, 2, 1;
    model = build_cloth_model(cloth);
    model.masses.assign(4, 1.0);
    start = cloth.vertices;
    TriangleMesh ground;
    ground.vertices.resize(3, 3);
    ground.vertices << -5, 0, -5, 5, 0, -5, 0, 0, 5;
    ground.faces.resize(1, 3);
    ground.faces << 0, 2, 1;
    obstacles.push_back({"ground", ground, {}});
    obstacle_start = {ground.vertices};
    obstacle_end = {ground.vertices};
  }
  StepContext context() const { return {&model, &start, &obstacles, &obstacle_start, &obstacle_end, 0}; }
};

/// Vertex 3 of the cloth against the ground triangle.
Collision vertex_on_ground(double w1, double w2) {
  Collision c;
  c.kind = PairKind::VertexFace;
  c.vertices = {VertexRef{0, 3}, VertexRef{1, 0}, VertexRef{1, 1}, VertexRef{1, 2}};
  c.parameters = {w1, w2};
  c.normal = Eigen::Vector3d::UnitY();
  return c;
}

}  // namespace

TEST_CASE("an impulse lifts a vertex that went through the ground back to the thickness", "[simulation][response]") {
  Fixture f;
  Vertices end = f.start;
  end.row(3) << 0.3, -0.05, 0.2;  // moved 0.1 sideways and through the ground
  ResponseSettings settings;
  settings.friction = 0;
  apply_impulses({vertex_on_ground(0.25, 0.25)}, f.context(), settings, end);
  CHECK(end(3, 1) == Approx(settings.thickness * settings.separation));
  CHECK(end(3, 0) == Approx(0.3));  // no friction: the sideways motion stays
  CHECK(end.topRows(3) == f.start.topRows(3));

  Vertices rubbing = f.start;
  rubbing.row(3) << 0.3, -0.05, 0.2;
  settings.friction = 0.5;
  apply_impulses({vertex_on_ground(0.25, 0.25)}, f.context(), settings, rubbing);
  // Friction removes 0.5 * push of the 0.1 sideways slide.
  const double push = settings.thickness * settings.separation + 0.05;
  CHECK(rubbing(3, 0) == Approx(0.3 - 0.5 * push));
}

TEST_CASE("a pair already apart by the thickness gets no impulse", "[simulation][response]") {
  Fixture f;
  Vertices end = f.start;
  apply_impulses({vertex_on_ground(0.25, 0.25)}, f.context(), {}, end);
  CHECK(end == f.start);
}

TEST_CASE("a collision naming a vertex or body that does not exist is refused", "[simulation][response][bad-input]") {
  Fixture f;
  Vertices end = f.start;
  for (const VertexRef bad : {VertexRef{0, 99}, VertexRef{0, -1}, VertexRef{1, 3}, VertexRef{2, 0}, VertexRef{-1, 0}}) {
    Collision c = vertex_on_ground(0.25, 0.25);
    c.vertices[1] = bad;
    CHECK_THROWS_WITH(apply_impulses({c}, f.context(), {}, end), Catch::Contains("does not exist"));
    FailSafe failsafe(static_cast<int>(f.start.rows()));
    CHECK_THROWS_WITH(failsafe.absorb({c}, f.context()), Catch::Contains("does not exist"));
  }
  CHECK(end == f.start);
}

TEST_CASE("the fail-safe freezes static contacts and carries vertices with a moving obstacle", "[simulation][response]") {
  Fixture f;
  Vertices end = f.start;
  end.row(3) << 0.3, -0.05, 0.2;
  FailSafe failsafe(4);
  CHECK(failsafe.absorb({vertex_on_ground(0.25, 0.25)}, f.context()) == 1);
  failsafe.apply(f.context(), end);
  CHECK(end.row(3) == f.start.row(3));
  CHECK(failsafe.absorb({vertex_on_ground(0.25, 0.25)}, f.context()) == 0);  // settled
  CHECK(failsafe.grouped_vertices() == 1);

  // Now the ground moves up 0.1 per step: the vertex is carried with it, escalating from static.
  f.obstacles[0].motion.translation = Eigen::Vector3d(0, 0.1, 0);
  f.obstacles[0].motion.moving_steps = 5;
  CHECK(failsafe.absorb({vertex_on_ground(0.25, 0.25)}, f.context()) == 1);
  failsafe.apply(f.context(), end);
  CHECK(end(3, 1) == Approx(f.start(3, 1) + 0.1));
}

TEST_CASE("conservative reports are dropped only when provably apart", "[simulation][response]") {
  Fixture f;
  Vertices end = f.start;
  Collision far = vertex_on_ground(-1, 1);  // garbage parameters, as an undecided report may carry
  far.conservative = true;
  ResponseSettings settings;
  std::vector<Collision> reports = {far};
  CHECK(discard_disproved(reports, f.context(), end, 0.004) == 1);  // 0.01 away and not moving: apart
  CHECK(reports.empty());

  reports = {far};
  end.row(3) << 0.2, -0.02, 0.2;  // crosses the ground during the step: must stay, with usable contact data
  CHECK(discard_disproved(reports, f.context(), end, 0.004) == 0);
  REQUIRE(reports.size() == 1);
  CHECK(reports[0].normal.isApprox(Eigen::Vector3d::UnitY()));
  CHECK(reports[0].parameters[0] >= 0.0);
  CHECK(reports[0].parameters[1] >= 0.0);
  CHECK(reports[0].parameters[0] + reports[0].parameters[1] <= 1.0);
  apply_impulses(reports, f.context(), settings, end);
  CHECK(end(3, 1) == Approx(settings.thickness * settings.separation));

  Collision decided = vertex_on_ground(0.25, 0.25);  // exact reports are never dropped
  reports = {decided};
  CHECK(discard_disproved(reports, f.context(), f.start, 0.004) == 0);
}

TEST_CASE("the start gap is measured along the contact normal at the contact point", "[simulation][response]") {
  Fixture f;  // vertex 3 is 0.01 above the ground
  CHECK(start_gap(vertex_on_ground(0.25, 0.25), f.context()) == Approx(0.01));
  Collision flipped = vertex_on_ground(0.25, 0.25);
  flipped.normal = -flipped.normal;
  CHECK(start_gap(flipped, f.context()) == Approx(-0.01));
}

TEST_CASE("the contact memory merges reports in canonical order and forgets pairs out of reach",
          "[simulation][response]") {
  Fixture f;
  auto on_ground_vertex = [](int cloth_vertex, double w1) {
    Collision c = vertex_on_ground(w1, 0.25);
    c.vertices[0].vertex = cloth_vertex;
    return c;
  };
  ContactMemory memory;
  memory.remember({on_ground_vertex(1, 0.1), on_ground_vertex(3, 0.1)});
  memory.remember({on_ground_vertex(0, 0.2), on_ground_vertex(3, 0.3)});  // 3 again: its new record replaces the old
  std::vector<Collision> expected = {on_ground_vertex(0, 0.2), on_ground_vertex(1, 0.1), on_ground_vertex(3, 0.3)};
  REQUIRE(memory.contacts().size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(memory.contacts()[i].vertices[0].vertex == expected[i].vertices[0].vertex);
    CHECK(memory.contacts()[i].parameters[0] == expected[i].parameters[0]);
  }
  std::vector<Collision> sorted = memory.contacts();
  sort_collisions(sorted);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    CHECK(sorted[i].vertices[0].vertex == memory.contacts()[i].vertices[0].vertex);
  }

  // Vertices 0 and 1 are 1 above the ground (the cloth triangle), vertex 3 is 0.01 above it.
  memory.forget_distant(f.context(), 0.5);
  REQUIRE(memory.contacts().size() == 1);
  CHECK(memory.contacts()[0].vertices[0].vertex == 3);
  memory.forget_distant(f.context(), 0.005);
  CHECK(memory.contacts().empty());
}
