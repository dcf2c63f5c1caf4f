// Run-time pair network (Jin et al., section 3.3.1, eqs. 22-25): min-max scaling to [-1, 1], logistic layers, the
// probability compared with the operating point. The forward pass runs over blocks of rows in structure-of-arrays
// form (inner loops over rows, so the compiler vectorizes them) and performs each neuron's sum in OpenNN's order
// (inputs in order, then the bias), so it reproduces OpenNN's calculate_outputs to the last bit on the same machine.
#include "clothcd/culling/pair_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "support/simd.hpp"
#include "support/simd_level.hpp"

namespace clothcd::learning {
namespace {

constexpr std::size_t kBlock = 64;

double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }

// OpenNN's Probability method clamps the output to [0, 1]; logistic outputs already lie there.
double clamp_probability(double p) { return p > 1.0 ? 1.0 : (p < 0.0 ? 0.0 : p); }

struct ModelFiles {
  std::string network;
  std::string card;
};

ModelFiles model_files(const std::string& model) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(model, error))
    throw std::runtime_error(model + ": no such model (a directory with network.xml and card.json, or a network.xml)");
  if (fs::is_directory(model, error)) return {(fs::path(model) / "network.xml").string(), (fs::path(model) / "card.json").string()};
  return {model, (fs::path(model).parent_path() / "card.json").string()};
}

}  // namespace

PairClassifier::PairClassifier(NetworkWeights weights, const OperatingPoint& operating_point,
                               const std::vector<std::string>& feature_names, const std::string& context)
    : weights_(std::move(weights)), feature_count_(feature_names.size()) {
  validate_network_weights(weights_, context);
  for (const DenseLayer& layer : weights_.layers)
    if (layer.outputs > kMaxLayerNeurons)
      throw std::runtime_error(context + ": a layer has " + std::to_string(layer.outputs) + " neurons, at most " +
                               std::to_string(kMaxLayerNeurons) + " are supported");
  for (const std::string& name : weights_.input_names) {
    const auto it = std::find(feature_names.begin(), feature_names.end(), name);
    if (it == feature_names.end())
      throw std::runtime_error(context + ": network input '" + name + "' is not one of the computed features");
    input_columns_.push_back(static_cast<std::size_t>(it - feature_names.begin()));
  }
  set_operating_point(operating_point);
}

void PairClassifier::set_operating_point(const OperatingPoint& operating_point) {
  if (!(operating_point.drop_below >= 0.0 && operating_point.drop_below <= operating_point.decision_threshold &&
        operating_point.decision_threshold <= 1.0 && operating_point.keep_from >= operating_point.decision_threshold &&
        std::isfinite(operating_point.keep_from)))
    throw std::invalid_argument(
        "operating point: need 0 <= drop_below <= decision_threshold <= 1 and a finite keep_from >= decision_threshold");
  operating_point_ = operating_point;
}

PairClassifier PairClassifier::load(const std::string& model, const FeatureSettings& settings) {
  const ModelFiles files = model_files(model);
  const std::vector<std::string> features = pair_feature_names(settings);
  const ModelCard card = read_model_card(files.card);
  if (card.feature_version != kPairFeatureVersion)
    throw std::runtime_error(files.card + ": trained on feature definition version " +
                             std::to_string(card.feature_version) + ", this build computes version " +
                             std::to_string(kPairFeatureVersion));
  if (card.features != features)
    throw std::runtime_error(files.card + ": trained on " + std::to_string(card.features.size()) +
                             " features that differ from the " + std::to_string(features.size()) + " computed here");
  NetworkWeights weights = read_network_weights(files.network);
  if (weights.input_names != card.inputs)
    throw std::runtime_error(files.network + ": the network has " + std::to_string(weights.input_count()) +
                             " inputs, its model card lists " + std::to_string(card.inputs.size()) +
                             " (or other names)");
  OperatingPoint point;
  point.drop_below = card.drop_below;
  point.decision_threshold = card.decision_threshold;
  point.keep_from = card.keep_from;
  try {
    return PairClassifier(std::move(weights), point, features, files.network);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(files.card + ": " + e.what());
  }
}

namespace {

// Probabilities of rows [begin, begin + n) of the batch, n <= kBlock.
[[gnu::always_inline]] inline void forward_rows(const NetworkWeights& weights,
                                                const std::vector<std::size_t>& input_columns,
                                                const PairFeatureBatch& batch, std::size_t begin, std::size_t n,
                                                double* out) {
  constexpr std::size_t kWidest = kMaxLayerNeurons > kMaxPairFeatures ? kMaxLayerNeurons : kMaxPairFeatures;
  double buffer_a[kWidest][kBlock];
  double buffer_b[kWidest][kBlock];
  for (std::size_t k = 0; k < input_columns.size(); ++k) {
    const double* x = batch.column(input_columns[k]) + begin;
    const double lo = weights.input_minimum[k], range = weights.input_maximum[k] - weights.input_minimum[k];
    for (std::size_t i = 0; i < n; ++i) buffer_a[k][i] = 2.0 * (x[i] - lo) / range - 1.0;
  }
  double(*in)[kBlock] = buffer_a;
  double(*result)[kBlock] = buffer_b;
  for (const DenseLayer& layer : weights.layers) {
    for (std::size_t j = 0; j < layer.outputs; ++j) {
      double* sum = result[j];
      std::fill(sum, sum + n, 0.0);
      for (std::size_t k = 0; k < layer.inputs; ++k) {
        const double w = layer.weights[k * layer.outputs + j];
        const double* x = in[k];
        for (std::size_t i = 0; i < n; ++i) sum[i] += x[i] * w;
      }
      const double b = layer.biases[j];
      for (std::size_t i = 0; i < n; ++i) sum[i] = logistic(sum[i] + b);
    }
    std::swap(in, result);
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = clamp_probability(in[0][i]);
}

// forward_rows compiled for the baseline, AVX2 and AVX-512: the same IEEE operations in the same order (the library
// is built without contraction into fused multiply-adds), so the same probabilities, more rows per instruction.
#define CLOTHCD_SIMD_KERNEL_FUNCTION forward_rows
#define CLOTHCD_SIMD_KERNEL_AVX512
#include "support/simd_versions.hpp"

void forward_block(const NetworkWeights& weights, const std::vector<std::size_t>& input_columns,
                   const PairFeatureBatch& batch, std::size_t begin, std::size_t n, double* out) {
  CLOTHCD_SIMD_DISPATCH(simd_level(), run_kernel(weights, input_columns, batch, begin, n, out));
}

}  // namespace

void PairClassifier::probabilities(const PairFeatureBatch& batch, double* out) const {
  if (batch.features != feature_count_) throw std::invalid_argument("pair classifier: batch has the wrong feature count");
  for (std::size_t begin = 0; begin < batch.rows; begin += kBlock)
    forward_block(weights_, input_columns_, batch, begin, std::min(kBlock, batch.rows - begin), out + begin);
}

void PairClassifier::decide(const PairFeatureBatch& batch, PairDecision* out) const {
  if (batch.features != feature_count_) throw std::invalid_argument("pair classifier: batch has the wrong feature count");
  double probability[kBlock];
  for (std::size_t begin = 0; begin < batch.rows; begin += kBlock) {
    const std::size_t n = std::min(kBlock, batch.rows - begin);
    forward_block(weights_, input_columns_, batch, begin, n, probability);
    for (std::size_t i = 0; i < n; ++i) out[begin + i] = decide(probability[i]);
  }
}

double reference_probability(const NetworkWeights& weights, const double* inputs) {
  std::vector<double> values(inputs, inputs + weights.input_count());
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = 2.0 * (values[k] - weights.input_minimum[k]) / (weights.input_maximum[k] - weights.input_minimum[k]) - 1.0;
  for (const DenseLayer& layer : weights.layers) {
    std::vector<double> next(layer.outputs);
    for (std::size_t j = 0; j < layer.outputs; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < layer.inputs; ++k) sum += values[k] * layer.weights[k * layer.outputs + j];
      next[j] = logistic(sum + layer.biases[j]);
    }
    values = std::move(next);
  }
  return clamp_probability(values[0]);
}

}  // namespace clothcd::learning
