// The clothcd program: help, info, convert, meshes, and one-line errors with a non-zero exit.
#include <catch2/catch.hpp>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

using clothcd::test::run_cli;
using clothcd::test::TempDir;

TEST_CASE("clothcd --help lists the subcommands", "[cli]") {
  const auto run = run_cli("--help");
  CHECK(run.exit_code == 0);
  for (const char* command : {"info", "convert", "meshes"}) CHECK(run.output.find(command) != std::string::npos);
  CHECK(run_cli("info --help").exit_code == 0);
  CHECK(run_cli("").exit_code != 0);
  CHECK(run_cli("no-such-command").exit_code != 0);
}

TEST_CASE("clothcd info and convert on a generated mesh", "[cli]") {
  TempDir dir;
  clothcd::save_mesh(clothcd::make_box(), dir / "box.obj");
  const auto info = run_cli("info '" + (dir / "box.obj").string() + "'");
  REQUIRE(info.exit_code == 0);
  CHECK(info.output.find("faces:            12") != std::string::npos);
  CHECK(info.output.find("watertight:       yes") != std::string::npos);

  const auto convert = run_cli("convert '" + (dir / "box.obj").string() + "' '" + (dir / "box.ply").string() + "'");
  REQUIRE(convert.exit_code == 0);
  CHECK(clothcd::load_mesh(dir / "box.ply").face_count() == 12);
}

TEST_CASE("clothcd errors are one line on stderr with a non-zero exit", "[cli][errors]") {
  TempDir dir;
  const auto missing = run_cli("info '" + (dir / "missing.obj").string() + "'");
  CHECK(missing.exit_code == 1);
  CHECK(missing.output.rfind("clothcd: error: ", 0) == 0);
  CHECK(missing.output.find('\n') == missing.output.size() - 1);
  clothcd::test::write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  CHECK(run_cli("convert '" + (dir / "nan.obj").string() + "' '" + (dir / "out.obj").string() + "'").exit_code == 1);
}

TEST_CASE("command-line mistakes are one clothcd error line with exit code 1", "[cli][errors]") {
  const auto unknown = run_cli("frobnicate x");
  CHECK(unknown.exit_code == 1);
  CHECK(unknown.output.rfind("clothcd: error: unknown command 'frobnicate' (commands: info, ", 0) == 0);
  for (const char* args : {"", "info", "info a b", "info --bogus x", "simplify a b --ratio nan", "bench"}) {
    INFO(args);
    const auto run = run_cli(args);
    CHECK(run.exit_code == 1);
    CHECK(run.output.find("error: ") != std::string::npos);
    CHECK(run.output.find('\n') == run.output.size() - 1);
  }
  CHECK(run_cli("info a b").output.find("clothcd: error: info: The following argument was not expected: b") == 0);
}

TEST_CASE("an empty item in a comma-separated list is an error, not skipped", "[cli][errors]") {
  TempDir dir;
  const std::string out = "gen-dataset --out '" + (dir / "pairs.csv").string() + "' --steps 1 ";
  for (const char* list : {"--scenes box,,box", "--scenes box,", "--cloths ,A", "--seeds 1,,2"}) {
    INFO(list);
    const auto run = run_cli(out + list);
    CHECK(run.exit_code == 1);
    CHECK(run.output.find("empty item in the comma-separated list") != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "pairs.csv"));
}

TEST_CASE("clothcd meshes fills the cache folder and writes an index", "[cli][models]") {
  TempDir dir;
  const auto run = run_cli("meshes --dir '" + (dir / "models").string() + "'");
  REQUIRE(run.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "models" / "index.csv"));
  CHECK(run.output.find("rabbit") != std::string::npos);
  CHECK(run.output.find("75408") != std::string::npos);
}

TEST_CASE("clothcd refuses out-of-range numbers before they wrap, run for ever or reach the library", "[cli][errors]") {
  TempDir dir;
  const std::string out = (dir / "out").string();
  const std::string data = "'" + (dir / "none.csv").string() + "' --out '" + out + "'";
  // Each command alone would wrap "-1" into 2^64 - 1 trials, pairs, rows or a seed, or accept an unusable value.
  for (const std::string& args :
       {"train " + data + " --trials -1", "train " + data + " --trials 1000000000", "train " + data + " --random-pairs -1",
        "train " + data + " --seed -1", "train " + data + " --max-epochs -5", "train " + data + " --max-neurons 65",
        "train " + data + " --rebalance 1e20", "gen-dataset --out '" + out + ".csv' --max-rows -1",
        "gen-dataset --out '" + out + ".csv' --seeds 1,-1", "gen-dataset --out '" + out + ".csv' --seed 18446744073709551616",
        "gen-dataset --out '" + out + ".csv' --steps 0", "simulate --scene box --resolution -5 --out '" + out + "'",
        "simulate --scene box --cloth D --resolution 5 --out '" + out + "'",
        "simulate --scene box --dt 1e10 --out '" + out + "'", std::string("simplify in.off out.obj --ratio -0.5"),
        std::string("simplify in.off out.obj --ratio nan"), std::string("simplify in.off out.obj --max-error inf"),
        std::string("obb in.off --method adaptive-simplified --simplify nan")}) {
    INFO(args);
    const auto run = run_cli(args);
    CHECK(run.exit_code != 0);
    // The message names the option (or, for dt, the setting).
    CHECK((run.output.find("--") != std::string::npos || run.output.find("time step dt") != std::string::npos));
  }
}

TEST_CASE("clothcd ccd on an empty query file is an error", "[cli][errors][ccd]") {
  TempDir dir;
  clothcd::test::write_file(dir / "empty.csv", "");
  const auto run = run_cli("ccd '" + (dir / "empty.csv").string() + "' --type vf");
  CHECK(run.exit_code == 1);
  CHECK(run.output.find("no queries") != std::string::npos);
}
