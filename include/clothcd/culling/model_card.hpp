#pragma once
/// @file
/// The model card written beside a trained pair network (MODEL_DIR/card.json): what the network takes, how it was
/// trained and its operating point. The runtime reads it to check the feature definition and to cull safely.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace clothcd::learning {

/// Contents of card.json.
struct ModelCard {
  int feature_version = 0;                    ///< kPairFeatureVersion of the features the network was trained on.
  std::size_t feature_count = 0;              ///< FeatureSettings::count used to compute the data set.
  std::vector<std::string> features;          ///< All feature names of the data set, in order.
  std::vector<std::string> inputs;            ///< The network's inputs (features minus dropped columns), in order.
  std::vector<std::string> dropped_columns;   ///< Constant feature columns removed before OpenNN saw the data.
  std::string dataset;                        ///< Data set file the network was trained on.
  std::size_t rows_training = 0;              ///< Rows per split.
  std::size_t rows_selection = 0;             ///< Rows per split.
  std::size_t rows_testing = 0;               ///< Rows per split.
  std::size_t hidden_neurons = 0;             ///< Chosen by incremental order selection.
  std::size_t max_neurons = 0;                ///< Searched 1..max_neurons.
  std::size_t trials = 0;                     ///< Trainings per neuron count (the best selection error is kept).
  unsigned long long seed = 0;                ///< Seed of the training.
  double decision_threshold = 0.5;            ///< Probability >= threshold: the network says the filters keep the pair.
  double drop_below = 0.0;                    ///< Probability < drop_below: the pair is dropped without any check.
  /// Probability >= keep_from: the pair skips the filters (OperatingPoint::keep_from). Cards without the field (written
  /// before it existed) read as decision_threshold.
  double keep_from = 0.5;
  std::vector<std::pair<std::string, double>> metrics;  ///< Named metrics (selection/testing accuracy, AUC, ...).
};

/// Writes the card as JSON; throws std::runtime_error naming the file on failure.
void write_model_card(const ModelCard& card, const std::string& path);

/// Reads a card written by write_model_card; throws std::runtime_error naming the file and the problem (missing,
/// malformed JSON, missing or mistyped field).
[[nodiscard]] ModelCard read_model_card(const std::string& path);

}  // namespace clothcd::learning
