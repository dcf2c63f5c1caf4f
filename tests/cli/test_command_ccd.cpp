// `clothcd ccd` on small generated query files: summary counts, JSON, per-query output and one-line errors.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

using clothcd::test::run_cli;
using clothcd::test::TempDir;
using clothcd::test::write_file;

namespace {

// Eight rows of one vertex-face query: the vertex at (1/4, 1/4) drops from z = 1 to z_end over the unit triangle.
std::string vertex_face_query(const std::string& z_end, int truth) {
  const std::string t = "," + std::to_string(truth) + "\n";
  return "1,4,1,4,1,1" + t + "0,1,0,1,0,1" + t + "1,1,0,1,0,1" + t + "0,1,1,1,0,1" + t + "1,4,1,4," + z_end + t +
         "0,1,0,1,0,1" + t + "1,1,0,1,0,1" + t + "0,1,1,1,0,1" + t;
}

// The summary's query, collision and ground-truth counts in `output`.
void check_counts(const std::string& output, int queries, int colliding, int false_positives, int false_negatives) {
  CHECK_THAT(output, Catch::Contains("queries:               " + std::to_string(queries)));
  CHECK_THAT(output, Catch::Contains("colliding:             " + std::to_string(colliding)));
  CHECK_THAT(output, Catch::Contains("false positives:       " + std::to_string(false_positives)));
  CHECK_THAT(output, Catch::Contains("false negatives:       " + std::to_string(false_negatives)));
}

}  // namespace

TEST_CASE("clothcd ccd summarises a generated query folder", "[ccd][cli]") {
  TempDir dir;
  std::filesystem::create_directories(dir / "vertex-face");
  // Colliding (ends below the face), separated (stops at z = 1/2), and a false ground truth of 0 for a colliding one.
  write_file(dir / "vertex-face/a.csv", vertex_face_query("-1,1", 1) + vertex_face_query("1,2", 0));
  write_file(dir / "vertex-face/b.csv", vertex_face_query("-1,2", 0));
  const auto run =
      run_cli("ccd '" + dir.path().string() + "' --filter combined --per-query '" + (dir / "out.csv").string() + "'");
  REQUIRE(run.exit_code == 0);
  check_counts(run.output, 3, 2, 1, 0);
  std::ifstream per_query(dir / "out.csv");
  std::stringstream buffer;
  buffer << per_query.rdbuf();
  const std::string lines = buffer.str();
  CHECK_THAT(lines, Catch::StartsWith("file,line,kind,truth,hit,state,toi,culled\n"));
  CHECK(std::count(lines.begin(), lines.end(), '\n') == 4);

  // The per-query file may not be one of the inputs (it would be truncated before it is read).
  const std::string before = vertex_face_query("-1,1", 1) + vertex_face_query("1,2", 0);
  const auto onto_input = run_cli("ccd '" + dir.path().string() + "' --per-query '" + (dir / "vertex-face/a.csv").string() + "'");
  CHECK(onto_input.exit_code != 0);
  CHECK_THAT(onto_input.output, Catch::Contains("would overwrite"));
  std::ifstream input(dir / "vertex-face/a.csv");
  std::stringstream kept;
  kept << input.rdbuf();
  CHECK(kept.str() == before);

  const auto json = run_cli("ccd '" + (dir / "vertex-face/a.csv").string() + "' --json --thickness 0.01");
  REQUIRE(json.exit_code == 0);
  const nlohmann::json summary = nlohmann::json::parse(json.output);
  CHECK(summary["schema"] == 1);
  CHECK(summary["queries"] == 2);
  CHECK(summary["false_negatives"] == 0);
  CHECK(summary["filter"] == "combined");

  // A path with a quote and a backslash stays valid JSON.
  std::filesystem::create_directories(dir / "we\"ird\\name/vertex-face");
  write_file(dir / "we\"ird\\name/vertex-face/a.csv", vertex_face_query("1,2", 1));
  const auto escaped = run_cli("ccd '" + (dir / "we\"ird\\name").string() + "' --json");
  REQUIRE(escaped.exit_code == 0);
  CHECK(nlohmann::json::parse(escaped.output)["path"] == (dir / "we\"ird\\name").string());
}

TEST_CASE("clothcd ccd decides queries with non-double coordinates on their exact values", "[ccd][cli]") {
  // The vertex drops through the hypotenuse x + y = 1 of the unit triangle: x = 1/2 + 5 * 2^-56 rounds up to
  // 1/2 + 2^-53 and y = 1/2 - 5 * 2^-56 rounds to 1/2 - 2^-54, so the rounded vertex passes just outside the triangle
  // (x + y = 1 + 2^-54), while the exact one touches its edge.
  const std::string xy = "36028797018963973,72057594037927936,36028797018963963,72057594037927936,";
  const std::string face = "0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n";
  TempDir dir;
  write_file(dir / "edge.csv", xy + "1,1,1\n" + face + xy + "-1,1,1\n" + face);
  for (const std::string options : {"--filter combined", "--filter none", "--thickness 1e-30"}) {
    INFO(options);
    const auto run = run_cli("ccd '" + (dir / "edge.csv").string() + "' --type vf " + options);
    REQUIRE(run.exit_code == 0);
    CHECK_THAT(run.output, Catch::Contains("false negatives:       0"));
    CHECK_THAT(run.output, Catch::Contains("inexact coordinates:   1"));
  }
}

TEST_CASE("clothcd ccd decides every query exactly unless --approximate", "[ccd][cli]") {
  // A vertex-face query on a small integer grid (found by search) that interval arithmetic cannot decide and that
  // misses by the exact reference: a miss by default, a conservative hit (a false positive) with --approximate.
  const char* points[8] = {"0,2,0", "1,0,0", "-1,1,2", "-2,2,-1", "0,-2,2", "-1,2,1", "1,1,-2", "0,-2,0"};
  std::string text;
  for (const char* p : points) {
    std::stringstream row(p);
    std::string coordinate;
    while (std::getline(row, coordinate, ',')) text += coordinate + ",1,";
    text += "0\n";
  }
  TempDir dir;
  write_file(dir / "undecided.csv", text);
  const auto fast =
      run_cli("ccd '" + (dir / "undecided.csv").string() + "' --type vf --filter combined --approximate");
  REQUIRE(fast.exit_code == 0);
  check_counts(fast.output, 1, 1, 1, 0);
  CHECK_THAT(fast.output, Catch::Contains("(1 conservative)"));
  CHECK_THAT(fast.output, Catch::Contains("reported as conservative hits"));
  const auto exact = run_cli("ccd '" + (dir / "undecided.csv").string() + "' --type vf --filter combined");
  REQUIRE(exact.exit_code == 0);
  check_counts(exact.output, 1, 0, 0, 0);
  CHECK_THAT(exact.output, Catch::Contains("(0 conservative)"));
}

TEST_CASE("clothcd ccd rejects malformed input with a one-line error", "[ccd][cli][errors]") {
  TempDir dir;
  write_file(dir / "bad.csv", "1,1,1,1,1\n");
  const auto columns = run_cli("ccd '" + (dir / "bad.csv").string() + "' --type vf");
  CHECK(columns.exit_code == 1);
  CHECK_THAT(columns.output, Catch::StartsWith("clothcd: error: ") && Catch::Contains("bad.csv:1:"));
  CHECK(columns.output.find('\n') == columns.output.size() - 1);
  write_file(dir / "short.csv", vertex_face_query("-1,1", 1).substr(0, 20) + "\n");
  CHECK(run_cli("ccd '" + (dir / "short.csv").string() + "' --type vf").exit_code == 1);
  write_file(dir / "ok.csv", vertex_face_query("-1,1", 1));
  CHECK(run_cli("ccd '" + (dir / "ok.csv").string() + "'").exit_code == 1);  // no --type, no kind folder
  CHECK(run_cli("ccd '" + (dir / "ok.csv").string() + "' --type xx").exit_code == 1);
  CHECK(run_cli("ccd '" + (dir / "ok.csv").string() + "' --type vf --filter bogus").exit_code == 1);
  CHECK(run_cli("ccd '" + (dir / "ok.csv").string() + "' --type vf --thickness -1").exit_code == 1);
  const auto approximate_thick =
      run_cli("ccd '" + (dir / "ok.csv").string() + "' --type vf --thickness 0.1 --approximate");
  CHECK(approximate_thick.exit_code == 1);
  CHECK_THAT(approximate_thick.output, Catch::Contains("--approximate changes only") && Catch::Contains("thickness"));
  CHECK(run_cli("ccd '" + (dir / "missing").string() + "'").exit_code == 1);
}

TEST_CASE("clothcd ccd reads a file larger than one chunk whole", "[ccd][cli]") {
  // 9,001 queries (more than two of the command's 4,096-query chunks): every third collides.
  TempDir dir;
  std::filesystem::create_directories(dir / "vertex-face");
  std::string text;
  const int queries = 9001;
  for (int k = 0; k < queries; ++k) text += k % 3 == 0 ? vertex_face_query("-1,1", 1) : vertex_face_query("1,2", 0);
  write_file(dir / "vertex-face/many.csv", text);
  const auto run = run_cli("ccd '" + dir.path().string() + "' --per-query '" + (dir / "out.csv").string() + "'");
  REQUIRE(run.exit_code == 0);
  check_counts(run.output, queries, 3001, 0, 0);
  std::ifstream per_query(dir / "out.csv");
  std::string line, last;
  int lines = 0;
  while (std::getline(per_query, line)) {
    ++lines;
    last = line;
  }
  CHECK(lines == queries + 1);
  CHECK_THAT(last, Catch::Contains("many.csv," + std::to_string(8 * (queries - 1) + 1) + ",vf,1,1,"));
}
