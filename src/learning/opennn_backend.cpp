// The OpenNN back-end: builds, trains, saves, loads and exports the paper's pair network (Jin et al., section 3.3.1:
// scaling layer with min-max to [-1, 1] (eq. 22), logistic perceptron layers (eqs. 23-24), binary probabilistic layer
// (eq. 25), normalized squared error (eq. 26), quasi-Newton BFGS (eqs. 27-32)).
// This is the ONLY file of clothcd that includes OpenNN's headers: they put `using namespace std` at global scope and
// OpenNN draws its initial weights from the global std::rand, so training is seeded here and runs in one thread.
#include "learning/opennn_backend.hpp"

#include "clothcd/culling/pair_classifier.hpp"
#include "culling/model_file_check.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include <opennn/opennn.h>

namespace clothcd::learning::backend {

struct OpennnNetwork::Impl {
  OpenNN::NeuralNetwork network;
};

OpennnNetwork::OpennnNetwork() : impl_(std::make_unique<Impl>()) {}
OpennnNetwork::~OpennnNetwork() = default;
OpennnNetwork::OpennnNetwork(OpennnNetwork&&) noexcept = default;
OpennnNetwork& OpennnNetwork::operator=(OpennnNetwork&&) noexcept = default;

namespace {

OpenNN::Instances::Use opennn_use(Split split) {
  switch (split) {
    case Split::Training: return OpenNN::Instances::Training;
    case Split::Selection: return OpenNN::Instances::Selection;
    case Split::Testing: return OpenNN::Instances::Testing;
  }
  return OpenNN::Instances::Unused;
}

OpenNN::Matrix<double> to_matrix(const std::vector<double>& row_major, std::size_t rows, std::size_t columns) {
  OpenNN::Matrix<double> matrix(rows, columns);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < columns; ++j) matrix(i, j) = row_major[i * columns + j];
  return matrix;
}

void check_data(const OpennnData& data) {
  const std::size_t inputs = data.input_names.size();
  if (inputs == 0) throw std::invalid_argument("OpenNN training: no input column");
  if (data.inputs.size() != data.targets.size() * inputs || data.splits.size() != data.targets.size())
    throw std::invalid_argument("OpenNN training: inputs, targets and splits disagree in row count");
  bool has_training = false, has_selection = false;
  for (const Split split : data.splits) {
    has_training |= split == Split::Training;
    has_selection |= split == Split::Selection;
  }
  if (!has_training || !has_selection) throw std::invalid_argument("OpenNN training: needs training and selection rows");
}

}  // namespace

OpennnNetwork OpennnNetwork::load(const std::string& path) {
  check_model_file_shape(path);
  OpennnNetwork result;
  try {
    result.impl_->network.set_display(false);
    result.impl_->network.load(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": OpenNN cannot load the model: " + e.what());
  }
  if (!result.impl_->network.get_multilayer_perceptron_pointer() || !result.impl_->network.get_scaling_layer_pointer() ||
      !result.impl_->network.get_probabilistic_layer_pointer())
    throw std::runtime_error(path + ": the model lacks the perceptron, scaling or probabilistic layer");
  return result;
}

void OpennnNetwork::save(const std::string& path) const {
  // NeuralNetwork::save goes through to_XML, whose scaling layer writes 6 significant digits; write_XML is the path the
  // project's patch gives 17 digits, so save/load is exact. The file is the same XML that NeuralNetwork::load reads.
  tinyxml2::XMLPrinter printer;
  impl_->network.write_XML(printer);
  std::ofstream file(path, std::ios::binary);
  file << "<?xml version=\"1.0\"?>\n" << printer.CStr();
  if (!file.flush()) throw std::runtime_error(path + ": cannot write the OpenNN model file");
}

std::size_t OpennnNetwork::input_count() const { return impl_->network.get_inputs_number(); }

std::vector<double> OpennnNetwork::outputs(const std::vector<double>& inputs, bool probability) const {
  const std::size_t columns = input_count();
  if (columns == 0 || inputs.size() % columns != 0)
    throw std::invalid_argument("OpenNN outputs: input size is not a multiple of the input count");
  OpenNN::ProbabilisticLayer* layer = impl_->network.get_probabilistic_layer_pointer();
  const OpenNN::ProbabilisticLayer::ProbabilisticMethod method = layer->get_probabilistic_method();
  if (probability) layer->set_probabilistic_method(OpenNN::ProbabilisticLayer::Probability);
  const OpenNN::Matrix<double> out = impl_->network.calculate_outputs(to_matrix(inputs, inputs.size() / columns, columns));
  layer->set_probabilistic_method(method);
  std::vector<double> result(out.get_rows_number());
  for (std::size_t i = 0; i < result.size(); ++i) result[i] = out(i, 0);
  return result;
}

NetworkWeights OpennnNetwork::export_weights() const {
  const OpenNN::NeuralNetwork& network = impl_->network;
  NetworkWeights weights;
  const OpenNN::Vector<std::string> names = network.get_inputs_pointer()->get_names();
  weights.input_names.assign(names.begin(), names.end());
  const OpenNN::ScalingLayer* scaling = network.get_scaling_layer_pointer();
  const auto methods = scaling->get_scaling_methods();
  const auto statistics = scaling->get_statistics();
  if (statistics.size() != weights.input_names.size())
    throw std::runtime_error("scaling layer size differs from the input count");
  for (std::size_t i = 0; i < statistics.size(); ++i) {
    if (methods[i] != OpenNN::ScalingLayer::MinimumMaximum)
      throw std::runtime_error("scaling of input '" + weights.input_names[i] + "' is not MinimumMaximum");
    weights.input_minimum.push_back(statistics[i].minimum);
    weights.input_maximum.push_back(statistics[i].maximum);
  }
  const OpenNN::MultilayerPerceptron* perceptron = network.get_multilayer_perceptron_pointer();
  for (std::size_t l = 0; l < perceptron->get_layers_number(); ++l) {
    const OpenNN::PerceptronLayer& layer = perceptron->get_layer(l);
    if (layer.get_activation_function() != OpenNN::PerceptronLayer::Logistic)
      throw std::runtime_error("perceptron layer " + std::to_string(l + 1) + " is not logistic");
    const OpenNN::Matrix<double> synaptic = layer.get_synaptic_weights();  // inputs x neurons
    const OpenNN::Vector<double> biases = layer.get_biases();
    DenseLayer dense;
    dense.inputs = synaptic.get_rows_number();
    dense.outputs = synaptic.get_columns_number();
    dense.weights.resize(dense.inputs * dense.outputs);
    for (std::size_t k = 0; k < dense.inputs; ++k)
      for (std::size_t j = 0; j < dense.outputs; ++j) dense.weights[k * dense.outputs + j] = synaptic(k, j);
    dense.biases.assign(biases.begin(), biases.end());
    weights.layers.push_back(std::move(dense));
  }
  const OpenNN::ProbabilisticLayer* probabilistic = network.get_probabilistic_layer_pointer();
  if (probabilistic->get_probabilistic_method() != OpenNN::ProbabilisticLayer::Binary)
    throw std::runtime_error("the probabilistic layer is not Binary");
  weights.decision_threshold = probabilistic->get_decision_threshold();
  return weights;
}

OpennnTraining OpennnTraining::run(const OpennnData& data, const OpennnTrainSettings& settings) {
  check_data(data);
  const std::size_t inputs = data.input_names.size();
  const std::size_t rows = data.targets.size();

  std::vector<double> table(rows * (inputs + 1));
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < inputs; ++j) table[i * (inputs + 1) + j] = data.inputs[i * inputs + j];
    table[i * (inputs + 1) + inputs] = data.targets[i];
  }
  OpenNN::DataSet data_set(to_matrix(table, rows, inputs + 1));
  data_set.set_display(false);
  OpenNN::Vector<std::string> variable_names(data.input_names.begin(), data.input_names.end());
  variable_names.push_back("filter_label");
  data_set.get_variables_pointer()->set_names(variable_names);
  OpenNN::Vector<OpenNN::Variables::Use> variable_uses(inputs + 1, OpenNN::Variables::Input);
  variable_uses[inputs] = OpenNN::Variables::Target;
  data_set.get_variables_pointer()->set_uses(variable_uses);
  OpenNN::Vector<OpenNN::Instances::Use> instance_uses(rows);
  for (std::size_t i = 0; i < rows; ++i) instance_uses[i] = opennn_use(data.splits[i]);
  data_set.get_instances_pointer()->set_uses(instance_uses);
  const OpenNN::Vector<OpenNN::Statistics<double>> statistics = data_set.scale_inputs_minimum_maximum();
  for (std::size_t j = 0; j < inputs; ++j)
    if (!(statistics[j].maximum > statistics[j].minimum))
      throw std::invalid_argument("OpenNN training: input '" + data.input_names[j] + "' is constant");

  std::srand(settings.seed);
  OpennnTraining result;
  OpenNN::NeuralNetwork& network = result.network.impl_->network;
  network.set(OpenNN::Vector<std::size_t>{inputs, settings.hidden_neurons, 1});
  network.set_display(false);
  network.get_inputs_pointer()->set_names(OpenNN::Vector<std::string>(data.input_names.begin(), data.input_names.end()));
  network.get_multilayer_perceptron_pointer()->set_layers_activation_function(
      OpenNN::Vector<OpenNN::PerceptronLayer::ActivationFunction>(2, OpenNN::PerceptronLayer::Logistic));
  network.construct_scaling_layer();
  network.get_scaling_layer_pointer()->set_statistics(statistics);
  network.get_scaling_layer_pointer()->set_scaling_methods(OpenNN::ScalingLayer::MinimumMaximum);
  network.get_scaling_layer_pointer()->set_display(false);
  network.construct_probabilistic_layer();
  network.get_probabilistic_layer_pointer()->set_probabilistic_method(OpenNN::ProbabilisticLayer::Binary);
  network.get_probabilistic_layer_pointer()->set_decision_threshold(settings.decision_threshold);

  OpenNN::TrainingStrategy strategy(&network, &data_set);
  strategy.set_display(false);
  OpenNN::QuasiNewtonMethod* quasi_newton = strategy.get_quasi_Newton_method_pointer();
  quasi_newton->set_inverse_Hessian_approximation_method(OpenNN::QuasiNewtonMethod::BFGS);
  quasi_newton->set_maximum_epochs_number(settings.max_epochs);
  quasi_newton->set_display(false);
  const OpenNN::OptimizationAlgorithm::Results outcome = strategy.perform_training();

  const OpenNN::LossIndex* loss = strategy.get_loss_index_pointer();
  result.training_error = loss->calculate_training_loss();
  result.selection_error = loss->calculate_selection_error();
  result.epochs = outcome.epochs_number;
  return result;
}

double opennn_area_under_curve(const std::vector<double>& labels, const std::vector<double>& scores) {
  if (labels.size() != scores.size()) throw std::invalid_argument("OpenNN AUC: labels and scores differ in size");
  const OpenNN::TestingAnalysis analysis;
  return analysis.calculate_area_under_curve(to_matrix(labels, labels.size(), 1), to_matrix(scores, scores.size(), 1));
}

}  // namespace clothcd::learning::backend
