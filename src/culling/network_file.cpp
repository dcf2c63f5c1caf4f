// Reading a trained network's XML (the file OpenNN 0.56.2 writes) without OpenNN: the run-time culler needs only the
// weights, so the core library parses the file itself with pugixml. The layout read here is OpenNN's: per perceptron
// layer, its synaptic weights as an inputs x neurons matrix in column-major order, then its biases; a test checks that
// the weights equal the ones OpenNN itself exports from the same file.
#include "clothcd/culling/network_weights.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <pugixml.hpp>

#include "clothcd/culling/pair_classifier.hpp"
#include "culling/model_file_check.hpp"

namespace clothcd::learning {
namespace {

constexpr std::size_t kMaxInputs = 1000;

// The whitespace-separated tokens of `element`'s text (none for a missing element or empty text).
std::vector<std::string> tokens_of(const pugi::xml_node& element) {
  std::vector<std::string> tokens;
  std::istringstream text(element.child_value());
  for (std::string token; text >> token;) tokens.push_back(token);
  return tokens;
}

// One finite number, else a clear error naming the element.
double number_of(const std::string& token, const char* name, const std::string& path) {
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size() || !std::isfinite(value))
    throw std::runtime_error(path + ": <" + name + "> holds '" + token + "', not a finite number");
  return value;
}

// The finite numbers in `element`.
std::vector<double> numbers_of(const pugi::xml_node& element, const char* name, const std::string& path) {
  std::vector<double> values;
  for (const std::string& token : tokens_of(element)) values.push_back(number_of(token, name, path));
  return values;
}

// The one finite number in `element`.
double single_number(const pugi::xml_node& element, const char* name, const std::string& path) {
  const std::vector<std::string> tokens = tokens_of(element);
  if (tokens.size() != 1)
    throw std::runtime_error(path + ": <" + name + "> must hold one number, it holds " + std::to_string(tokens.size()));
  return number_of(tokens[0], name, path);
}

// The count in `element`: one integer in [1, limit], else a clear error naming the element.
std::size_t count_of(const pugi::xml_node& element, const char* name, std::size_t limit, const std::string& path) {
  const std::vector<std::string> tokens = tokens_of(element);
  char* end = nullptr;
  const long long value = tokens.size() == 1 ? std::strtoll(tokens[0].c_str(), &end, 10) : 0;
  if (tokens.size() != 1 || end != tokens[0].c_str() + tokens[0].size() || value < 1 ||
      static_cast<unsigned long long>(value) > limit)
    throw std::runtime_error(path + ": <" + name + "> must hold one whole number in 1.." + std::to_string(limit) +
                             (tokens.empty() ? std::string(", it is empty") : ", it holds '" + tokens[0] + "'"));
  return static_cast<std::size_t>(value);
}

// The text of `element`, which must be `expected`.
void require_word(const pugi::xml_node& element, const char* name, const std::string& expected,
                  const std::string& path) {
  const std::vector<std::string> tokens = tokens_of(element);
  if (tokens.size() != 1 || tokens[0] != expected)
    throw std::runtime_error(path + ": <" + name + "> must be " + expected + ", it is '" +
                             std::string(element.child_value()) + "' (not supported)");
}

// Input names and min-max scaling: <Inputs> lists one <Item><Name> per input, <ScalingLayer> one <ScalingNeuron>.
void read_inputs(const pugi::xml_node& root, const std::string& path, NetworkWeights& weights) {
  const pugi::xml_node inputs = root.child("Inputs");
  const std::size_t count = count_of(inputs.child("InputsNumber"), "InputsNumber", kMaxInputs, path);
  for (const pugi::xml_node& item : inputs.children("Item")) weights.input_names.push_back(item.child_value("Name"));
  if (weights.input_names.size() != count)
    throw std::runtime_error(path + ": <Inputs> names " + std::to_string(weights.input_names.size()) + " inputs, " +
                             "<InputsNumber> says " + std::to_string(count));
  const pugi::xml_node scaling = root.child("ScalingLayer");
  if (count_of(scaling.child("ScalingNeuronsNumber"), "ScalingNeuronsNumber", kMaxInputs, path) != count)
    throw std::runtime_error(path + ": <ScalingNeuronsNumber> differs from <InputsNumber> (" + std::to_string(count) + ")");
  for (const pugi::xml_node& neuron : scaling.children("ScalingNeuron")) {
    weights.input_minimum.push_back(single_number(neuron.child("Minimum"), "Minimum", path));
    weights.input_maximum.push_back(single_number(neuron.child("Maximum"), "Maximum", path));
    require_word(neuron.child("ScalingMethod"), "ScalingMethod", "MinimumMaximum", path);
  }
  if (weights.input_minimum.size() != count)
    throw std::runtime_error(path + ": the scaling layer lists " + std::to_string(weights.input_minimum.size()) +
                             " <ScalingNeuron> elements for " + std::to_string(count) + " inputs");
}

// The perceptron layers: <Architecture> (inputs, then each layer's width), one Logistic activation per layer, and
// exactly the parameters the architecture needs.
void read_layers(const pugi::xml_node& root, const std::string& path, NetworkWeights& weights) {
  const pugi::xml_node perceptron = root.child("MultilayerPerceptron");
  std::vector<std::size_t> architecture;
  for (const std::string& token : tokens_of(perceptron.child("Architecture"))) {
    char* end = nullptr;
    const long long width = std::strtoll(token.c_str(), &end, 10);
    if (end != token.c_str() + token.size() || width < 1 || static_cast<std::size_t>(width) > kMaxInputs)
      throw std::runtime_error(path + ": <Architecture> holds '" + token + "', not a width in 1.." +
                               std::to_string(kMaxInputs));
    architecture.push_back(static_cast<std::size_t>(width));
  }
  if (architecture.size() < 2 || architecture.front() != weights.input_count())
    throw std::runtime_error(path + ": <Architecture> must list the " + std::to_string(weights.input_count()) +
                             " inputs and then at least one layer width");
  std::size_t needed = 0;
  for (std::size_t l = 1; l < architecture.size(); ++l) {
    if (architecture[l] > kMaxLayerNeurons)
      throw std::runtime_error(path + ": a layer of <Architecture> has " + std::to_string(architecture[l]) +
                               " neurons, at most " + std::to_string(kMaxLayerNeurons) + " are supported");
    needed += (architecture[l - 1] + 1) * architecture[l];
  }
  const std::vector<std::string> activations = tokens_of(perceptron.child("LayersActivationFunction"));
  if (activations.size() != architecture.size() - 1)
    throw std::runtime_error(path + ": <LayersActivationFunction> names " + std::to_string(activations.size()) +
                             " activations for " + std::to_string(architecture.size() - 1) + " layers");
  for (const std::string& activation : activations)
    if (activation != "Logistic")
      throw std::runtime_error(path + ": activation '" + activation + "' is not supported (only Logistic)");
  const std::vector<double> parameters = numbers_of(perceptron.child("Parameters"), "Parameters", path);
  if (parameters.size() != needed)
    throw std::runtime_error(path + ": <Parameters> holds " + std::to_string(parameters.size()) +
                             " numbers, the architecture needs " + std::to_string(needed) + " (truncated or edited model)");
  std::size_t at = 0;
  for (std::size_t l = 1; l < architecture.size(); ++l) {
    DenseLayer layer;
    layer.inputs = architecture[l - 1];
    layer.outputs = architecture[l];
    layer.weights.resize(layer.inputs * layer.outputs);
    for (std::size_t j = 0; j < layer.outputs; ++j)  // column-major: neuron j's weights are consecutive
      for (std::size_t k = 0; k < layer.inputs; ++k) layer.weights[k * layer.outputs + j] = parameters[at++];
    layer.biases.assign(parameters.begin() + static_cast<long>(at),
                        parameters.begin() + static_cast<long>(at + layer.outputs));
    at += layer.outputs;
    weights.layers.push_back(std::move(layer));
  }
}

}  // namespace

NetworkWeights read_network_weights(const std::string& path) {
  check_model_file_shape(path);
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_file(path.c_str());
  if (parsed.status == pugi::status_file_not_found || parsed.status == pugi::status_io_error)
    throw std::runtime_error(path + ": model file not found or unreadable");
  if (!parsed)
    throw std::runtime_error(path + ": not a well-formed XML model (truncated or corrupt): " +
                             std::string(parsed.description()) + " at byte " + std::to_string(parsed.offset));
  const pugi::xml_node root = document.child("NeuralNetwork");
  if (!root) throw std::runtime_error(path + ": no <NeuralNetwork> element: not an OpenNN model");
  for (const char* part : {"Inputs", "ScalingLayer", "MultilayerPerceptron", "ProbabilisticLayer"})
    if (!root.child(part)) throw std::runtime_error(path + ": the model lacks <" + part + ">");
  NetworkWeights weights;
  read_inputs(root, path, weights);
  read_layers(root, path, weights);
  const pugi::xml_node probabilistic = root.child("ProbabilisticLayer");
  if (count_of(probabilistic.child("ProbabilisticNeuronsNumber"), "ProbabilisticNeuronsNumber", kMaxLayerNeurons,
               path) != weights.layers.back().outputs)
    throw std::runtime_error(path + ": <ProbabilisticNeuronsNumber> differs from the last layer's width");
  require_word(probabilistic.child("ProbabilisticMethod"), "ProbabilisticMethod", "Binary", path);
  weights.decision_threshold = single_number(probabilistic.child("DecisionThreshold"), "DecisionThreshold", path);
  validate_network_weights(weights, path);
  return weights;
}

}  // namespace clothcd::learning
