// `clothcd train` and `clothcd evaluate` end to end on a tiny random-pair data set, and their error exits.
#include <catch2/catch.hpp>

#include "support/test_support.hpp"

#include <filesystem>
#include <string>

namespace fs = std::filesystem;

using clothcd::test::run_cli;

TEST_CASE("clothcd train and evaluate run end to end", "[learning][cli]") {
  const clothcd::test::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string data = (dir / "pairs.csv").string(), model = (dir / "model").string();
  const auto train = run_cli("train \"" + data + "\" --random-pairs 600 --seed 3 --max-neurons 2 --trials 1 --max-epochs 60 --out \"" +
                             model + "\"");
  REQUIRE(train.exit_code == 0);
  CHECK(train.output.find("chosen hidden neurons") != std::string::npos);
  for (const char* file : {"network.xml", "card.json", "neurons.csv", "neurons.png"}) CHECK(fs::exists(fs::path(model) / file));
  const auto evaluate = run_cli("evaluate \"" + model + "\" \"" + data + "\"");
  REQUIRE(evaluate.exit_code == 0);
  const std::string& report = evaluate.output;
  CHECK(report.find("accuracy") != std::string::npos);
  CHECK(report.find("real collisions") != std::string::npos);
  CHECK(fs::exists(fs::path(model) / "roc.csv"));
  CHECK(fs::exists(fs::path(model) / "roc.png"));

  const auto missing_model = run_cli("evaluate \"" + (dir / "missing").string() + "\" \"" + data + "\"");
  CHECK(missing_model.exit_code != 0);
  CHECK(missing_model.output.find("clothcd: error:") != std::string::npos);
  const auto missing_data = run_cli("train \"" + (dir / "missing.csv").string() + "\" --out \"" + model + "\"");
  CHECK(missing_data.exit_code != 0);
  CHECK(missing_data.output.find("cannot open the data set") != std::string::npos);
  fs::remove_all(dir);
}
