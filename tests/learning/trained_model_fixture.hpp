#pragma once
// One small pair network trained once per test run (tiny: 1200 random pairs, up to 3 neurons, 1 trial) and shared by
// the runtime, evaluation and bad-model tests.

#include <filesystem>
#include <string>

#include "clothcd/learning/network_training.hpp"
#include "culling/pair_test_data.hpp"
#include "support/test_support.hpp"

namespace clothcd::learning::test {

/// The shared model: its data set, training report and directory.
struct TrainedModel {
  PairDataset dataset;
  TrainingReport report;
  std::string directory;
};

/// Settings of the shared model.
inline TrainingSettings small_training_settings() {
  TrainingSettings settings;
  settings.max_neurons = 3;
  settings.trials = 1;
  settings.max_epochs = 150;
  settings.seed = 5;
  return settings;
}

/// Trains the shared model on first use into a temporary directory of this process (test cases run as parallel
/// processes, so the directory must not be shared).
inline const TrainedModel& trained_model() {
  static const clothcd::test::TempDir folder;
  static const TrainedModel model = [] {
    TrainedModel m;
    m.dataset = make_pair_dataset(1200, 11);
    m.directory = (folder / "model").string();
    m.report = train_pair_network(m.dataset, small_training_settings(), m.directory, "random pairs (test)");
    return m;
  }();
  return model;
}

}  // namespace clothcd::learning::test
