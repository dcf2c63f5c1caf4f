// `clothcd train` and `clothcd evaluate` end to end on a tiny random-pair data set, and their error exits.
#include <catch2/catch.hpp>

#include "support/test_support.hpp"

#include <filesystem>
#include <fstream>
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
  for (const char* file : {"network.xml", "card.json", "neurons.csv", "neurons.svg"}) CHECK(fs::exists(fs::path(model) / file));
  const auto evaluate = run_cli("evaluate \"" + model + "\" \"" + data + "\"");
  REQUIRE(evaluate.exit_code == 0);
  const std::string& report = evaluate.output;
  CHECK(report.find("accuracy") != std::string::npos);
  CHECK(report.find("real collisions") != std::string::npos);
  CHECK(fs::exists(fs::path(model) / "roc.csv"));
  CHECK(fs::exists(fs::path(model) / "roc.svg"));
  CHECK(report.find("AUC - (undefined") == std::string::npos);

  // A testing split of one class: no AUC and no sensitivity to report (they were printed as 0 and 1).
  std::ifstream in(data);
  std::ofstream one_class(dir / "one_class.csv");
  std::string line;
  std::getline(in, line);
  one_class << line << '\n';
  while (std::getline(in, line)) {
    const std::size_t last = line.rfind(',');
    const bool testing = line.compare(last + 1, std::string::npos, "testing") == 0;
    // filter_label is the fifth column from the end (filter_label, exact_label, type, scene, split).
    std::size_t at = line.size();
    for (int k = 0; k < 5; ++k) at = line.rfind(',', at - 1);
    const bool label_one = line.compare(at + 1, 2, "1,") == 0;
    if (!testing || !label_one) one_class << line << '\n';
  }
  one_class.close();
  const auto single = run_cli("evaluate \"" + model + "\" \"" + (dir / "one_class.csv").string() + "\" --roc \"" +
                              (dir / "roc1").string() + "\"");
  REQUIRE(single.exit_code == 0);
  CHECK(single.output.find("AUC - (undefined: one class)") != std::string::npos);
  CHECK(single.output.find("sensitivity - (no label 1)") != std::string::npos);

  for (const std::string& roc : {dir.string(), (dir / "sub/").string(), std::string()}) {  // folders would get ".csv"
    const auto folder = run_cli("evaluate \"" + model + "\" \"" + data + "\" --roc \"" + roc + "\"");
    CHECK(folder.exit_code != 0);
    CHECK(folder.output.find("file name prefix") != std::string::npos);
  }

  const auto missing_model = run_cli("evaluate \"" + (dir / "missing").string() + "\" \"" + data + "\"");
  CHECK(missing_model.exit_code != 0);
  CHECK(missing_model.output.find("clothcd: error:") != std::string::npos);
  const auto missing_data = run_cli("train \"" + (dir / "missing.csv").string() + "\" --out \"" + model + "\"");
  CHECK(missing_data.exit_code != 0);
  CHECK(missing_data.output.find("cannot open the data set") != std::string::npos);
  fs::remove_all(dir);
}
