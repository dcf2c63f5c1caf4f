// Shape and finiteness checks of exported network weights (the runtime refuses NaN weights or broken layer chains).
#include "clothcd/culling/network_weights.hpp"

#include <cmath>
#include <stdexcept>

namespace clothcd::learning {
namespace {

void require(bool condition, const std::string& context, const std::string& problem) {
  if (!condition) throw std::runtime_error(context + ": " + problem);
}

bool all_finite(const std::vector<double>& values) {
  for (const double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

void validate_network_weights(const NetworkWeights& weights, const std::string& context) {
  const std::size_t inputs = weights.input_count();
  require(inputs > 0, context, "the network has no input");
  require(weights.input_minimum.size() == inputs && weights.input_maximum.size() == inputs, context,
          "the scaling layer has " + std::to_string(weights.input_minimum.size()) + " entries for " +
              std::to_string(inputs) + " inputs");
  require(all_finite(weights.input_minimum) && all_finite(weights.input_maximum), context,
          "non-finite value in the scaling layer");
  for (std::size_t i = 0; i < inputs; ++i) {
    require(weights.input_maximum[i] > weights.input_minimum[i], context,
            "input '" + weights.input_names[i] + "' has an empty scaling range (constant column)");
    // A range wider than the largest double would scale every input to 0 or NaN: every pair kept, nothing culled.
    require(std::isfinite(weights.input_maximum[i] - weights.input_minimum[i]), context,
            "input '" + weights.input_names[i] + "' has a scaling range wider than the largest double");
  }
  require(!weights.layers.empty(), context, "the network has no perceptron layer");
  std::size_t previous = inputs;
  for (std::size_t l = 0; l < weights.layers.size(); ++l) {
    const DenseLayer& layer = weights.layers[l];
    const std::string name = "perceptron layer " + std::to_string(l + 1);
    require(layer.inputs == previous, context, name + " takes " + std::to_string(layer.inputs) + " inputs, expected " +
                                                   std::to_string(previous));
    require(layer.outputs > 0 && layer.weights.size() == layer.inputs * layer.outputs &&
                layer.biases.size() == layer.outputs,
            context, name + " has inconsistent weight or bias counts");
    require(all_finite(layer.weights) && all_finite(layer.biases), context, name + " has a non-finite weight or bias");
    previous = layer.outputs;
  }
  require(previous == 1, context, "the network has " + std::to_string(previous) + " outputs, expected 1");
  require(std::isfinite(weights.decision_threshold) && weights.decision_threshold >= 0.0 &&
              weights.decision_threshold <= 1.0,
          context, "the decision threshold is not in [0, 1]");
}

}  // namespace clothcd::learning
