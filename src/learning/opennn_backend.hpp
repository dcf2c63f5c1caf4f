#pragma once
// Private wrapper around OpenNN 0.56.2: the only door to it. No OpenNN type appears here, so this header can be
// included anywhere; opennn_backend.cpp is the single translation unit of clothcd that includes OpenNN's headers.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "clothcd/culling/network_weights.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::learning::backend {

/// A classification data set as OpenNN sees it: inputs and one 0/1 target per row, each row in one split.
struct OpennnData {
  std::vector<std::string> input_names;  ///< One name per input column.
  std::vector<double> inputs;            ///< rows x input_names.size(), row-major.
  std::vector<double> targets;           ///< One 0/1 target per row.
  std::vector<Split> splits;             ///< One split per row.
};

/// One training run of the paper's network: scaling (min-max to [-1, 1]) -> logistic hidden layer -> logistic output ->
/// binary probabilistic layer; normalized squared error; quasi-Newton with BFGS.
struct OpennnTrainSettings {
  std::size_t hidden_neurons = 1;   ///< Neurons in the hidden perceptron layer.
  unsigned seed = 1;                ///< Seeds std::rand, which OpenNN uses for the initial weights.
  std::size_t max_epochs = 1000;    ///< Quasi-Newton iteration limit.
  double decision_threshold = 0.5;  ///< Stored in the binary probabilistic layer.
};

/// A network held by OpenNN (trained here or loaded from its XML).
class OpennnNetwork {
 public:
  OpennnNetwork();
  ~OpennnNetwork();
  OpennnNetwork(OpennnNetwork&&) noexcept;
  OpennnNetwork& operator=(OpennnNetwork&&) noexcept;

  /// Loads OpenNN's XML through OpenNN itself; throws std::runtime_error naming the file when OpenNN rejects it.
  [[nodiscard]] static OpennnNetwork load(const std::string& path);
  /// Writes OpenNN's XML (17 significant digits with the project's patch); throws when the file cannot be written.
  void save(const std::string& path) const;
  /// OpenNN's calculate_outputs on rows x inputs (row-major): the probability when `probability` is true (the
  /// probabilistic layer switched to Probability), else the layer's own binary 0/1 decision. One value per row.
  [[nodiscard]] std::vector<double> outputs(const std::vector<double>& inputs, bool probability) const;
  /// The weights of the loaded layers as plain arrays, for clothcd's own forward pass.
  [[nodiscard]] NetworkWeights export_weights() const;
  /// Number of inputs of the network.
  [[nodiscard]] std::size_t input_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend struct OpennnTraining;
};

/// What one training run gives back.
struct OpennnTraining {
  OpennnNetwork network;         ///< The trained network.
  double training_error = 0.0;   ///< Normalized squared error on the training rows.
  double selection_error = 0.0;  ///< Normalized squared error on the selection rows.
  std::size_t epochs = 0;        ///< Quasi-Newton iterations run.

  /// Trains a fresh network on `data` (needs training and selection rows, no constant input column).
  [[nodiscard]] static OpennnTraining run(const OpennnData& data, const OpennnTrainSettings& settings);
};

/// OpenNN's own AUC (O(positives x negatives)) of scores against 0/1 labels, for cross-checking ours in tests.
[[nodiscard]] double opennn_area_under_curve(const std::vector<double>& labels, const std::vector<double>& scores);

}  // namespace clothcd::learning::backend
