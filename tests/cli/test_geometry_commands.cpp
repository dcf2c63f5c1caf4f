// The `clothcd simplify` and `clothcd obb` commands: output, files written, errors.
#include <catch2/catch.hpp>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

using namespace clothcd;

TEST_CASE("clothcd simplify writes the simplified mesh", "[geometry][cli]") {
  const test::TempDir dir;
  save_mesh(make_uv_sphere(1.0, 32, 16), dir / "sphere.obj");
  const auto run = test::run_cli("simplify '" + (dir / "sphere.obj").string() + "' '" + (dir / "out.obj").string() +
                                 "' --faces 100 --hausdorff");
  INFO(run.output);
  CHECK(run.exit_code == 0);
  CHECK(run.output.find("-> 100") != std::string::npos);
  CHECK(run.output.find("hausdorff:") != std::string::npos);
  CHECK(load_mesh(dir / "out.obj").face_count() == 100);
  const auto missing = test::run_cli("simplify '" + (dir / "sphere.obj").string() + "' '" + (dir / "o.obj").string() + "'");
  CHECK(missing.exit_code != 0);
  const auto bad = test::run_cli("simplify '" + (dir / "nope.ply").string() + "' '" + (dir / "o.obj").string() +
                                 "' --ratio 0.5");
  CHECK(bad.exit_code != 0);
  const auto no_faces = test::run_cli("simplify '" + (dir / "sphere.obj").string() + "' '" + (dir / "o.obj").string() +
                                      "' --faces 0");
  CHECK(no_faces.exit_code != 0);
  CHECK(no_faces.output.find("--faces") != std::string::npos);
}

TEST_CASE("clothcd obb prints the box, its volume and tau", "[geometry][cli]") {
  const test::TempDir dir;
  save_mesh(make_box(Eigen::Vector3d(1, 2, 3)), dir / "box.obj");
  for (const char* method : {"aabb", "sphere", "covariance", "adaptive", "adaptive-simplified", "tight"}) {
    const auto run = test::run_cli("obb '" + (dir / "box.obj").string() + "' --method " + method + " --json");
    INFO(run.output);
    CHECK(run.exit_code == 0);
    CHECK(run.output.find("\"tau\": ") != std::string::npos);
  }
  const auto tight = test::run_cli("obb '" + (dir / "box.obj").string() + "' --method tight");
  CHECK(tight.output.find("tau:          1\n") != std::string::npos);
  CHECK(test::run_cli("obb '" + (dir / "box.obj").string() + "' --method nonsense").exit_code != 0);
}

TEST_CASE("obb and simplify say how many zero-area faces they dropped, and JSON paths are escaped", "[geometry][cli]") {
  const test::TempDir dir;
  // A tetrahedron plus one face with a repeated vertex index, in a file whose name needs JSON escapes.
  const std::string name = "te\"tra\\x.off";
  test::write_file(dir / name, "OFF\n4 5 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 0 1\n");
  const std::string path = "'" + (dir / name).string() + "'";
  const auto json = test::run_cli("obb " + path + " --json");
  REQUIRE(json.exit_code == 0);
  CHECK(json.output.find("te\\\"tra\\\\x.off\",\n") != std::string::npos);
  CHECK(json.output.find("\"degenerate_faces_dropped\": 1\n") != std::string::npos);
  CHECK(test::run_cli("obb " + path).output.find("dropped:      1 zero-area faces") != std::string::npos);
  const auto simplified = test::run_cli("simplify " + path + " '" + (dir / "out.obj").string() + "' --ratio 0.5");
  CHECK(simplified.exit_code == 0);
  CHECK(simplified.output.find("dropped:      1 zero-area faces") != std::string::npos);
}
