// The run-time network reader (no OpenNN) against OpenNN itself on the committed model: the same weights bit for bit,
// and the same probabilities on seeded random feature rows inside and outside the scaling ranges.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/culling/network_weights.hpp"
#include "clothcd/culling/pair_classifier.hpp"
#include "learning/opennn_backend.hpp"

using namespace clothcd::learning;

namespace {

std::string committed_network() {
  return (std::filesystem::path(clothcd::learning::default_network_model_dir()) / "network.xml").string();
}

}  // namespace

TEST_CASE("the OpenNN-free reader gives OpenNN's own weights for the committed model", "[learning][runtime][opennn]") {
  const std::string path = committed_network();
  const NetworkWeights ours = read_network_weights(path);
  const NetworkWeights opennn = backend::OpennnNetwork::load(path).export_weights();
  CHECK(ours.input_names == opennn.input_names);
  CHECK(ours.input_minimum == opennn.input_minimum);
  CHECK(ours.input_maximum == opennn.input_maximum);
  CHECK(ours.decision_threshold == opennn.decision_threshold);
  REQUIRE(ours.layers.size() == opennn.layers.size());
  for (std::size_t l = 0; l < ours.layers.size(); ++l) {
    CHECK(ours.layers[l].inputs == opennn.layers[l].inputs);
    CHECK(ours.layers[l].outputs == opennn.layers[l].outputs);
    CHECK(ours.layers[l].weights == opennn.layers[l].weights);
    CHECK(ours.layers[l].biases == opennn.layers[l].biases);
  }
}

TEST_CASE("the run-time culler's probabilities equal OpenNN's outputs on the committed model",
          "[learning][runtime][opennn]") {
  const std::string path = committed_network();
  const NetworkWeights weights = read_network_weights(path);
  const PairClassifier classifier(weights, OperatingPoint{}, weights.input_names, path);
  const std::size_t rows = 1000, inputs = weights.input_count();
  std::mt19937_64 random(7);
  PairFeatureBatch batch;
  batch.resize(rows, inputs);
  std::vector<double> row_major(rows * inputs);
  for (std::size_t k = 0; k < inputs; ++k) {
    const double lo = weights.input_minimum[k], hi = weights.input_maximum[k], range = hi - lo;
    std::uniform_real_distribution<double> value(lo - 0.5 * range, hi + 0.5 * range);
    for (std::size_t i = 0; i < rows; ++i) row_major[i * inputs + k] = batch.column(k)[i] = value(random);
  }
  std::vector<double> ours(rows);
  classifier.probabilities(batch, ours.data());
  const std::vector<double> opennn = backend::OpennnNetwork::load(path).outputs(row_major, true);
  REQUIRE(opennn.size() == rows);
  double worst = 0.0;
  for (std::size_t i = 0; i < rows; ++i) worst = std::max(worst, std::abs(ours[i] - opennn[i]));
  CHECK(worst <= 1e-15);
  // The rows span both sides of the decision threshold, so the comparison covers both verdicts.
  CHECK(std::count_if(ours.begin(), ours.end(), [](double p) { return p < 0.5; }) > 0);
  CHECK(std::count_if(ours.begin(), ours.end(), [](double p) { return p >= 0.5; }) > 0);
}
