// OpenNN smoke test: the real OpenNN library is linked and works end to end. A tiny two-input data set, the paper's
// network (scaling, logistic perceptron layers, binary probabilistic layer) trained by quasi-Newton BFGS, saved through
// OpenNN, loaded back through OpenNN, and every output equal bit for bit.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "learning/opennn_backend.hpp"

namespace {

using clothcd::learning::Split;
using clothcd::learning::backend::OpennnData;
using clothcd::learning::backend::OpennnNetwork;
using clothcd::learning::backend::OpennnTraining;
using clothcd::learning::backend::OpennnTrainSettings;

// Points in the square [-1, 2] x [-3, 1]; the class is "above the line x1 = 0.5 x0 - 1", learnable by a tiny network.
OpennnData make_tiny_data(std::size_t rows) {
  OpennnData data;
  data.input_names = {"x0", "x1"};
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u0(-1.0, 2.0), u1(-3.0, 1.0);
  for (std::size_t i = 0; i < rows; ++i) {
    const double x0 = u0(rng), x1 = u1(rng);
    data.inputs.push_back(x0);
    data.inputs.push_back(x1);
    data.targets.push_back(x1 > 0.5 * x0 - 1.0 ? 1.0 : 0.0);
    data.splits.push_back(i % 5 < 3 ? Split::Training : (i % 5 == 3 ? Split::Selection : Split::Testing));
  }
  return data;
}

std::string temp_model_path(const char* name) {
  return (std::filesystem::temp_directory_path() / (std::string("clothcd_smoke_") + name + ".xml")).string();
}

}  // namespace

TEST_CASE("OpenNN trains the paper's network, and save/load reproduces its outputs bit for bit", "[learning][opennn]") {
  const OpennnData data = make_tiny_data(120);
  OpennnTrainSettings settings;
  settings.hidden_neurons = 3;
  settings.seed = 7;
  settings.max_epochs = 200;
  const OpennnTraining trained = OpennnTraining::run(data, settings);

  CHECK(trained.training_error < 0.5);  // NSE: 1 would be "predicts the mean"
  CHECK(trained.epochs > 0);
  const std::vector<double> probability = trained.network.outputs(data.inputs, true);
  const std::vector<double> decision = trained.network.outputs(data.inputs, false);
  REQUIRE(probability.size() == data.targets.size());
  std::size_t correct = 0;
  for (std::size_t i = 0; i < probability.size(); ++i) {
    REQUIRE(probability[i] >= 0.0);
    REQUIRE(probability[i] <= 1.0);
    REQUIRE(decision[i] == (probability[i] < 0.5 ? 0.0 : 1.0));
    correct += decision[i] == data.targets[i];
  }
  CHECK(correct >= probability.size() * 9 / 10);

  const std::string path = temp_model_path("roundtrip");
  trained.network.save(path);
  const OpennnNetwork loaded = OpennnNetwork::load(path);
  std::remove(path.c_str());
  REQUIRE(loaded.input_count() == 2);
  const std::vector<double> probability_loaded = loaded.outputs(data.inputs, true);
  const std::vector<double> decision_loaded = loaded.outputs(data.inputs, false);
  REQUIRE(probability_loaded.size() == probability.size());
  for (std::size_t i = 0; i < probability.size(); ++i) {
    REQUIRE(probability_loaded[i] == probability[i]);
    REQUIRE(decision_loaded[i] == decision[i]);
  }
}

TEST_CASE("OpenNN training is deterministic for a seed", "[learning][opennn]") {
  const OpennnData data = make_tiny_data(60);
  OpennnTrainSettings settings;
  settings.hidden_neurons = 2;
  settings.seed = 3;
  settings.max_epochs = 50;
  const OpennnTraining first = OpennnTraining::run(data, settings);
  const OpennnTraining second = OpennnTraining::run(data, settings);
  REQUIRE(first.training_error == second.training_error);
  REQUIRE(first.network.outputs(data.inputs, true) == second.network.outputs(data.inputs, true));
  settings.seed = 4;
  const OpennnTraining other = OpennnTraining::run(data, settings);
  CHECK(other.network.outputs(data.inputs, true) != first.network.outputs(data.inputs, true));
}

TEST_CASE("OpenNN load of a missing model is a clear error", "[learning][opennn]") {
  REQUIRE_THROWS_WITH(OpennnNetwork::load("/nonexistent/clothcd/model.xml"),
                      Catch::Contains("/nonexistent/clothcd/model.xml") && Catch::Contains("cannot load"));
}
