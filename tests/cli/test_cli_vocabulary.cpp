// The clothcd program speaks one vocabulary: every subcommand's --json is one parseable object with "schema": 1, the
// shared options have the same names and choices everywhere, and a wrong value lists the choices --help shows.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

using clothcd::test::run_cli;
using clothcd::test::TempDir;
using clothcd::test::write_file;

namespace {

// Runs `arguments` (which include --json) and returns its stdout parsed; checks the schema and command name.
nlohmann::json json_of(const std::string& command, const std::string& arguments) {
  INFO(command << ' ' << arguments);
  const auto run = run_cli(command + " " + arguments + " --json", true);
  REQUIRE(run.exit_code == 0);
  nlohmann::json report;
  REQUIRE_NOTHROW(report = nlohmann::json::parse(run.output));
  CHECK(report.is_object());
  CHECK(report["schema"] == 1);
  CHECK(report["command"] == command);
  return report;
}

// One vertex-face query of the public benchmark's CSV format: a vertex falling through the unit triangle.
std::string falling_vertex_query() {
  const std::string t = ",1\n";
  return "1,4,1,4,1,1" + t + "0,1,0,1,0,1" + t + "1,1,0,1,0,1" + t + "0,1,1,1,0,1" + t + "1,4,1,4,-1,1" + t +
         "0,1,0,1,0,1" + t + "1,1,0,1,0,1" + t + "0,1,1,1,0,1" + t;
}

}  // namespace

TEST_CASE("every reporting subcommand prints one JSON object with --json", "[cli][json]") {
  TempDir dir;
  const std::string box = "'" + (dir / "box.obj").string() + "'";
  clothcd::save_mesh(clothcd::make_box(), dir / "box.obj");
  clothcd::TriangleMesh moved = clothcd::make_box();
  moved.vertices.col(2).array() += 0.25;
  clothcd::save_mesh(moved, dir / "moved.obj");
  clothcd::test::write_file(dir / "query.csv", falling_vertex_query());

  CHECK(json_of("info", box)["faces"] == 12);
  CHECK(json_of("convert", box + " '" + (dir / "box.ply").string() + "'")["faces"] == 12);
  const nlohmann::json meshes = json_of("meshes", "--cache '" + clothcd::test::test_model_dir().string() + "'");
  CHECK(meshes["models"].size() >= 10);
  CHECK(json_of("simplify", box + " '" + (dir / "simple.obj").string() + "' --faces 8 --hausdorff")["faces_after"] <= 12);
  CHECK(json_of("obb", box + " --method covariance")["volume"].get<double>() > 0.0);
  CHECK(json_of("ccd", "'" + (dir / "query.csv").string() + "' --type vf")["false_negatives"] == 0);
  const nlohmann::json detect = json_of("detect", box + " '" + (dir / "moved.obj").string() + "' --thickness 0.01");
  CHECK(detect["vertex_face"].is_array());
  CHECK(detect["edge_edge"].is_array());
  const nlohmann::json simulate =
      json_of("simulate", "--scene box --resolution 4 --steps 2 --no-pictures --quiet --out '" +
                              (dir / "sim").string() + "'");
  CHECK(simulate["steps"] == 2);
  CHECK(simulate["intersecting_steps"] == 0);
  const std::string pairs = "'" + (dir / "pairs.csv").string() + "'";
  CHECK(json_of("gen-dataset", "--out " + pairs + " --steps 3 --max-rows 300 --quiet --cache '" +
                                   clothcd::test::test_model_dir().string() + "'")["rows"] > 0);
  const std::string model = "'" + (dir / "model").string() + "'";
  const std::string random = "'" + (dir / "random.csv").string() + "'";
  const nlohmann::json train = json_of("train", random + " --random-pairs 400 --max-neurons 1 --trials 1 "
                                                "--max-epochs 20 --quiet --out " + model);
  CHECK(train["hidden_neurons"] == 1);
  const nlohmann::json evaluate = json_of("evaluate", model + " " + random);
  CHECK(evaluate["rows"] > 0);
  CHECK(evaluate["filter_confusion"].contains("true_positive"));
}

TEST_CASE("a wrong choice lists the same names --help shows", "[cli][errors]") {
  const std::vector<std::string> filters{"none", "nonpenetration", "projection", "combined", "network"};
  const std::vector<std::string> hierarchies{"sphere-root-aabb", "aabb", "aabb-obb"};
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {"detect a.obj b.obj --filter", filters},   {"ccd q.csv --filter", filters},
      {"simulate --out x --filter", filters},     {"detect a.obj b.obj --bvh", hierarchies},
      {"simulate --out x --bvh", hierarchies},    {"ccd q.csv --type", {"vf", "ee"}},
      {"evaluate m d --split", {"training", "selection", "testing"}},
      {"obb m --method", {"aabb", "sphere", "covariance", "adaptive", "adaptive-simplified", "tight"}},
      {"simulate --out x --cloth", {"A", "B", "C"}}};
  for (const auto& [prefix, names] : cases) {
    INFO(prefix);
    const std::string command = prefix.substr(0, prefix.find(' '));
    const auto help = run_cli(command + " --help");
    const auto wrong = run_cli(prefix + " bogus");
    CHECK(wrong.exit_code == 1);
    CHECK_THAT(wrong.output, Catch::StartsWith("clothcd: error: "));
    for (const std::string& name : names) {
      CHECK_THAT(help.output, Catch::Contains(name));
      CHECK_THAT(wrong.output, Catch::Contains(name));
    }
  }
}

TEST_CASE("the shared options have one spelling, and the old ones stay hidden", "[cli]") {
  for (const char* command : {"detect", "ccd", "simulate"}) {
    INFO(command);
    const std::string help = run_cli(std::string(command) + " --help").output;
    CHECK_THAT(help, Catch::Contains("--filter") && Catch::Contains("--network") && Catch::Contains("combined"));
    for (const char* old : {"--culling", "--network-model", "--model-dir", "--model "}) CHECK(help.find(old) == std::string::npos);
  }
  for (const char* command : {"meshes", "simulate", "gen-dataset", "obb"}) {
    INFO(command);
    CHECK_THAT(run_cli(std::string(command) + " --help").output, Catch::Contains("--cache"));
  }
  for (const char* command : {"simulate", "gen-dataset", "train"}) {
    INFO(command);
    CHECK_THAT(run_cli(std::string(command) + " --help").output, Catch::Contains("--quiet"));
  }
  CHECK_THAT(run_cli("simulate --help").output, Catch::Contains("Exit code") && Catch::Contains("intersecting"));
  TempDir dir;
  // The old spellings still parse: --culling with its old value, --network-model and --model-dir.
  const auto old = run_cli("simulate --scene box --resolution 3 --steps 1 --no-pictures --quiet --culling filters "
                           "--model-dir '" + clothcd::test::test_model_dir().string() + "' --out '" +
                           (dir / "sim").string() + "'");
  CHECK(old.exit_code == 0);
  CHECK(old.output.find('\r') == std::string::npos);  // stderr is no terminal here: no bar drawn in place
  const auto needs = run_cli("simulate --scene box --network-model m --out '" + (dir / "sim").string() + "'");
  CHECK(needs.exit_code == 1);
  CHECK_THAT(needs.output, Catch::Contains("--network needs --filter network"));
}

TEST_CASE("the old --exact of detect and ccd is a hidden no-op, refused with --approximate", "[cli]") {
  TempDir dir;
  clothcd::TriangleMesh start = clothcd::make_grid(4, 4);
  clothcd::TriangleMesh end = start;
  end.vertices.col(2).array() -= 0.5;
  end.vertices(5, 2) += 1.0;  // one vertex rises through its neighbours' faces
  clothcd::save_mesh(start, dir / "t0.ply");
  clothcd::save_mesh(end, dir / "t1.ply");
  std::filesystem::create_directories(dir / "queries/vertex-face");
  // The vertex at (1/4, 1/4) drops from z = 1 to z = -1 through the unit triangle.
  write_file(dir / "queries/vertex-face/a.csv",
             "1,4,1,4,1,1,1\n0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n1,4,1,4,-1,1,1\n0,1,0,1,0,1,1\n"
             "1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n");
  const std::string detect = "detect '" + (dir / "t0.ply").string() + "' '" + (dir / "t1.ply").string() + "'";
  const std::string ccd = "ccd '" + (dir / "queries").string() + "'";
  for (const std::string& command : {detect, ccd}) {
    INFO(command);
    const auto help = run_cli(command + " --help");
    CHECK_THAT(help.output, Catch::Contains("--approximate") && Catch::Contains("--exact, which asked for it"));
    CHECK(help.output.find("  --exact ") == std::string::npos);
    const auto plain = run_cli(command + " --json", true);
    const auto exact = run_cli(command + " --exact --json", true);
    REQUIRE(plain.exit_code == 0);
    REQUIRE(exact.exit_code == 0);
    const auto plain_report = nlohmann::json::parse(plain.output);
    const auto exact_report = nlohmann::json::parse(exact.output);
    CHECK(exact_report["exact"] == true);
    for (const char* key : {"vertex_face", "edge_edge", "colliding"}) {
      CHECK(exact_report.contains(key) == plain_report.contains(key));
      if (plain_report.contains(key)) CHECK(exact_report[key] == plain_report[key]);
    }
    const auto both = run_cli(command + " --exact --approximate");
    CHECK(both.exit_code != 0);
    CHECK_THAT(both.output, Catch::Contains("excludes"));
  }
}

TEST_CASE("output paths are checked before the work starts", "[cli][errors]") {
  TempDir dir;
  clothcd::save_mesh(clothcd::make_box(), dir / "box.obj");
  const std::string box = "'" + (dir / "box.obj").string() + "'";
  const std::string nowhere = "'" + (dir / "no/such/folder").string();
  for (const std::string& args :
       {"simplify " + box + " " + nowhere + "/out.obj' --ratio 0.5", "convert " + box + " " + nowhere + "/out.ply'",
        "convert " + box + " '" + (dir / "out.stl").string() + "'",
        "detect " + box + " " + box + " --out " + nowhere + "/out.json'",
        "train '" + (dir / "pairs.csv").string() + "' --random-pairs 100 --out '" + (dir / "box.obj").string() + "'"}) {
    INFO(args);
    const auto run = run_cli(args);
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.output, Catch::StartsWith("clothcd: error: "));
  }
  CHECK_FALSE(std::filesystem::exists(dir / "pairs.csv"));  // train stopped before writing its random pairs
  const auto approximate = run_cli("detect " + box + " " + box + " --thickness 0.1 --approximate");
  CHECK(approximate.exit_code == 1);
  CHECK_THAT(approximate.output, Catch::Contains("--approximate changes only"));
}
