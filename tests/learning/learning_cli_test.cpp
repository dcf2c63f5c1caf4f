// `clothcd train` and `clothcd evaluate` end to end on a tiny random-pair data set, and their error exits.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

int run(const std::string& arguments, const std::string& output) {
  const std::string command = std::string("\"") + CLOTHCD_CLI_PATH + "\" " + arguments + " > \"" + output + "\" 2>&1";
  const int status = std::system(command.c_str());
  return status == 0 ? 0 : 1;
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("clothcd train and evaluate run end to end", "[learning][cli]") {
  const fs::path dir = fs::temp_directory_path() / "clothcd_learning_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string data = (dir / "pairs.csv").string(), model = (dir / "model").string(), log = (dir / "log.txt").string();
  REQUIRE(run("train \"" + data + "\" --random-pairs 600 --seed 3 --max-neurons 2 --trials 1 --max-epochs 60 --out \"" +
                  model + "\"",
              log) == 0);
  CHECK(read_text(log).find("chosen hidden neurons") != std::string::npos);
  for (const char* file : {"network.xml", "card.json", "neurons.csv", "neurons.png"}) CHECK(fs::exists(fs::path(model) / file));
  REQUIRE(run("evaluate \"" + model + "\" \"" + data + "\"", log) == 0);
  const std::string report = read_text(log);
  CHECK(report.find("accuracy") != std::string::npos);
  CHECK(report.find("real collisions") != std::string::npos);
  CHECK(fs::exists(fs::path(model) / "roc.csv"));
  CHECK(fs::exists(fs::path(model) / "roc.png"));

  CHECK(run("evaluate \"" + (dir / "missing").string() + "\" \"" + data + "\"", log) != 0);
  CHECK(read_text(log).find("clothcd: error:") != std::string::npos);
  CHECK(run("train \"" + (dir / "missing.csv").string() + "\" --out \"" + model + "\"", log) != 0);
  CHECK(read_text(log).find("cannot open the data set") != std::string::npos);
  fs::remove_all(dir);
}
