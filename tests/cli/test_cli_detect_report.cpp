// `clothcd detect`'s JSON report is written collision by collision, in exactly the bytes of the whole document dumped
// at once, and a step beyond --max-collisions ends with one error line and exit code 1.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

using clothcd::test::run_cli;
using clothcd::test::TempDir;

namespace {

// A 6 x 6 grid (t0.obj) whose vertices all end at its centre (t1.obj): thousands of collisions of both kinds.
void write_collapsing_grid(const TempDir& dir) {
  clothcd::TriangleMesh grid = clothcd::make_grid(6, 6);
  clothcd::save_mesh(grid, dir / "t0.obj");
  const Eigen::RowVector3d centre = grid.vertices.colwise().mean();
  for (Eigen::Index v = 0; v < grid.vertices.rows(); ++v) grid.vertices.row(v) = centre;
  clothcd::save_mesh(grid, dir / "t1.obj");
}

}  // namespace

TEST_CASE("detect --json and --out write the report of a dumped document, byte for byte", "[cli][json]") {
  TempDir dir;
  write_collapsing_grid(dir);
  const std::string step = "'" + (dir / "t0.obj").string() + "' '" + (dir / "t1.obj").string() + "'";
  const auto run = run_cli("detect " + step + " --json --out '" + (dir / "report.json").string() + "'", true);
  REQUIRE(run.exit_code == 0);
  const auto report = nlohmann::ordered_json::parse(run.output);
  // The same bytes as the parsed document dumped whole with an indent of 2 (the layout of every --json report).
  CHECK(report.dump(2) + "\n" == run.output);
  CHECK(clothcd::test::read_file(dir / "report.json") == run.output);
  REQUIRE(report["vertex_face"].size() > 100);
  REQUIRE(report["edge_edge"].size() > 100);
  CHECK(report["counts"]["vertex_face"] == report["vertex_face"].size());
  CHECK(report["counts"]["edge_edge"] == report["edge_edge"].size());
  const clothcd::TriangleMesh grid = clothcd::make_grid(6, 6);
  for (const auto& c : report["vertex_face"]) {
    CHECK(c["toi"] == 1.0);  // the cloth meets only where it ends, in one point
    const int face = c["pair"][1].get<int>();
    REQUIRE(face >= 0);
    REQUIRE(face < grid.face_count());
    for (int k = 0; k < 3; ++k) CHECK(c["face_vertices"][k] == grid.faces(face, k));
  }
}

TEST_CASE("detect beyond --max-collisions is one error line naming the budget, exit code 1", "[cli][errors]") {
  TempDir dir;
  write_collapsing_grid(dir);
  const std::string step = "'" + (dir / "t0.obj").string() + "' '" + (dir / "t1.obj").string() + "'";
  const auto run = run_cli("detect " + step + " --max-collisions 100 --json");
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.output, Catch::StartsWith("clothcd: error: collision detection stopped"));
  CHECK_THAT(run.output, Catch::Contains("max_collisions = 100"));
  CHECK(run.output.find('\n') == run.output.size() - 1);
  CHECK(run_cli("detect " + step + " --max-collisions 0").exit_code == 1);
}
