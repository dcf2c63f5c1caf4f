#pragma once
/// @file
/// The weights of a trained pair network as plain arrays: what clothcd's own forward pass evaluates.

#include <cstddef>
#include <string>
#include <vector>

namespace clothcd::learning {

/// One fully connected layer with logistic activation: out_j = 1 / (1 + exp(-(sum_k in_k * W(k, j) + b_j))).
struct DenseLayer {
  std::size_t inputs = 0;        ///< Inputs of the layer.
  std::size_t outputs = 0;       ///< Neurons of the layer.
  std::vector<double> weights;   ///< inputs x outputs, row-major: W(k, j) = weights[k * outputs + j].
  std::vector<double> biases;    ///< One bias per neuron.
};

/// A network as OpenNN stores it for the pair classifier: min-max scaling to [-1, 1], logistic layers, one output
/// (the probability that the pair survives the filters) and the decision threshold of the binary probabilistic layer.
struct NetworkWeights {
  std::vector<std::string> input_names;  ///< One name per input, in input order (clothcd feature names).
  std::vector<double> input_minimum;     ///< Per input: the minimum of the scaling layer (x -> 2 (x - min) / (max - min) - 1).
  std::vector<double> input_maximum;     ///< Per input: the maximum of the scaling layer (> minimum).
  std::vector<DenseLayer> layers;        ///< Hidden layer(s) then the one-neuron output layer, all logistic.
  double decision_threshold = 0.5;       ///< Threshold of the binary probabilistic layer.

  /// Number of inputs.
  [[nodiscard]] std::size_t input_count() const { return input_names.size(); }
};

/// Checks shapes (layer chaining, one output, minimum < maximum) and that every number is finite; throws
/// std::runtime_error "<context>: <problem>" otherwise.
void validate_network_weights(const NetworkWeights& weights, const std::string& context);

/// Reads a trained network's XML (as OpenNN 0.56.2 writes it) without OpenNN: the file must be well-formed, every
/// number of the scaling, perceptron and probabilistic layers finite, the layer sizes consistent (at most
/// kMaxLayerNeurons neurons per layer), the scaling min-max, the activations logistic and the probabilistic layer
/// binary. Throws std::runtime_error naming the file and the problem.
[[nodiscard]] NetworkWeights read_network_weights(const std::string& path);

}  // namespace clothcd::learning
