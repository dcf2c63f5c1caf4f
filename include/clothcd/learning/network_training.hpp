#pragma once
/// @file
/// Training of the pair network as the paper does it (Jin et al., sections 3.3.1 and 4.2): constant feature columns
/// dropped, OpenNN's scaling / logistic perceptron / binary probabilistic network trained by quasi-Newton BFGS on the
/// normalized squared error, and incremental order selection of the hidden neuron count (1..N, several trials each,
/// the best selection error wins). Then the safe operating point is chosen on the selection split.

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "clothcd/culling/model_card.hpp"
#include "clothcd/learning/classification_metrics.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::learning {

/// Settings of `clothcd train`.
struct TrainingSettings {
  std::size_t max_neurons = 10;      ///< Incremental order selection searches 1..max_neurons hidden neurons.
  std::size_t trials = 3;            ///< Trainings per neuron count from different seeds; the lowest selection error counts.
  unsigned long long seed = 1;       ///< Seed of every trial (trial seeds derive from it): same seed, same model.
  std::size_t max_epochs = 1000;     ///< Quasi-Newton iteration limit per training.
  double decision_threshold = 0.5;   ///< Threshold of the binary probabilistic layer.
  double drop_margin = 0.5;          ///< drop_below = drop_margin x the lowest probability of a real collision (selection).
  /// keep_from = 1 - keep_margin x (1 - the highest probability of a pair the filters remove) (selection), just above.
  double keep_margin = 0.5;
  std::size_t feature_count = 15;    ///< FeatureSettings::count the data set was made with (checked against its header).
};

/// One step of the incremental order selection.
struct NeuronCountResult {
  std::size_t neurons = 0;         ///< Hidden neurons.
  double training_error = 0.0;     ///< Normalized squared error on the training split (of the best trial).
  double selection_error = 0.0;    ///< Normalized squared error on the selection split (of the best trial).
  std::size_t best_trial = 0;      ///< Which trial (0-based) gave the lowest selection error.
};

/// What training produced; the files are written to the output directory.
struct TrainingReport {
  std::vector<NeuronCountResult> curve;  ///< One entry per neuron count, 1..max_neurons.
  ModelCard card;                        ///< Also written as card.json.
  ConfusionMatrix selection_confusion;   ///< Against the filter label at the decision threshold.
  ConfusionMatrix testing_confusion;     ///< Against the filter label at the decision threshold.
  /// AUC on the testing split against the filter label; NaN when it is undefined (no testing rows, or one class).
  double testing_auc = std::numeric_limits<double>::quiet_NaN();
};

/// Progress callback: (finished trainings, total trainings, neurons of the current step).
using TrainingProgress = std::function<void(std::size_t done, std::size_t total, std::size_t neurons)>;

/// Trains on `dataset` and writes OUT_DIR/network.xml (OpenNN's XML), card.json, neurons.csv and neurons.png
/// (training and selection error per neuron count). `dataset_name` is recorded in the card. Throws
/// std::invalid_argument for a data set without training or selection rows, without both classes in training, or
/// whose feature header differs from pair_feature_names({settings.feature_count}); std::runtime_error on I/O errors.
[[nodiscard]] TrainingReport train_pair_network(const PairDataset& dataset, const TrainingSettings& settings,
                                                const std::string& out_dir, const std::string& dataset_name,
                                                const TrainingProgress& progress = {});

}  // namespace clothcd::learning
