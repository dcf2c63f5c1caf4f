// Training of the pair network (Jin et al., section 3.3.1 steps (1)-(5) and section 4.2, Figure 12): constant columns
// dropped, then incremental order selection: for 1..N hidden neurons, several quasi-Newton BFGS trainings from
// different seeds, the lowest selection error per count, and the count with the lowest selection error overall
// (OpenNN's IncrementalOrder criterion, run as our own loop so every count is trained, progress can be shown and each
// trial is seeded on its own). The safe operating point is then chosen on the selection split: no pair the exact CCD
// finds colliding may fall below the drop threshold.
#include "clothcd/learning/network_training.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include "clothcd/culling/pair_classifier.hpp"
#include "clothcd/render/svg_chart.hpp"
#include "learning/opennn_backend.hpp"

namespace clothcd::learning {
namespace {

backend::OpennnData opennn_data(const PairDataset& dataset, const std::vector<std::size_t>& columns) {
  backend::OpennnData data;
  for (const std::size_t c : columns) data.input_names.push_back(dataset.feature_names[c]);
  data.inputs.reserve(dataset.row_count() * columns.size());
  for (std::size_t i = 0; i < dataset.row_count(); ++i) {
    for (const std::size_t c : columns) data.inputs.push_back(dataset.row(i)[c]);
    data.targets.push_back(dataset.filter_label[i]);
  }
  data.splits = dataset.split;
  return data;
}

void check_dataset(const PairDataset& dataset, const TrainingSettings& settings) {
  if (dataset.feature_names != pair_feature_names(FeatureSettings{settings.feature_count}))
    throw std::invalid_argument("the data set's feature columns are not the " + std::to_string(settings.feature_count) +
                                " pair features of definition version " + std::to_string(kPairFeatureVersion));
  if (settings.max_neurons < 1 || settings.max_neurons > kMaxLayerNeurons)
    throw std::invalid_argument("max neurons must be in 1.." + std::to_string(kMaxLayerNeurons));
  if (settings.trials < 1) throw std::invalid_argument("trials must be at least 1");
  if (!(settings.decision_threshold >= 0.0 && settings.decision_threshold <= 1.0))
    throw std::invalid_argument("the decision threshold must be in [0, 1]");
  if (!(settings.drop_margin >= 0.0 && settings.drop_margin <= 1.0 && settings.keep_margin >= 0.0 &&
        settings.keep_margin <= 1.0))
    throw std::invalid_argument("the drop and keep margins must be in [0, 1]");
  const ClassBalance balance = class_balance(dataset);
  const auto training = static_cast<std::size_t>(Split::Training), selection = static_cast<std::size_t>(Split::Selection);
  if (balance.rows[selection] == 0) throw std::invalid_argument("the data set has no selection rows");
  if (balance.filter_positive[training] == 0 || balance.filter_positive[training] == balance.rows[training])
    throw std::invalid_argument("the training split needs rows of both filter labels");
}

// Seed of one trial: distinct for every (seed, neurons, trial), fitting std::srand's unsigned.
unsigned trial_seed(unsigned long long seed, std::size_t neurons, std::size_t trial) {
  unsigned long long z = seed * 0x9E3779B97F4A7C15ULL + neurons * 0xBF58476D1CE4E5B9ULL + trial * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<unsigned>(z ^ (z >> 32));
}

// drop_below: drop_margin x the lowest probability of a real collision on the selection split (or of a pair the
// filters keep when the split has no real collision); never above the decision threshold.
double choose_drop_below(const PairDataset& dataset, const std::vector<double>& probability,
                         const TrainingSettings& settings) {
  double lowest_exact = std::numeric_limits<double>::infinity(), lowest_kept = lowest_exact;
  for (std::size_t i = 0; i < dataset.row_count(); ++i) {
    if (dataset.split[i] != Split::Selection) continue;
    if (dataset.exact_label[i] == 1) lowest_exact = std::min(lowest_exact, probability[i]);
    if (dataset.filter_label[i] == 1) lowest_kept = std::min(lowest_kept, probability[i]);
  }
  const double lowest = std::isfinite(lowest_exact) ? lowest_exact : lowest_kept;
  if (!std::isfinite(lowest)) return 0.0;
  return std::min(settings.drop_margin * lowest, settings.decision_threshold);
}

// keep_from: above the highest probability of a selection-split pair the filters remove, by keep_margin of its distance
// to 1 (the mirror of drop_below's margin), so that no such pair skips the filters there and few do on new data; never
// below the decision threshold; above 1 (nothing kept) when such a pair has probability 1.
double choose_keep_from(const PairDataset& dataset, const std::vector<double>& probability,
                        const TrainingSettings& settings) {
  double highest_removed = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < dataset.row_count(); ++i)
    if (dataset.split[i] == Split::Selection && dataset.filter_label[i] == 0)
      highest_removed = std::max(highest_removed, probability[i]);
  if (!std::isfinite(highest_removed)) return settings.decision_threshold;
  const double above = std::nextafter(1.0 - settings.keep_margin * (1.0 - highest_removed), 2.0);
  return std::max(above, settings.decision_threshold);
}

struct SplitScores {
  std::vector<int> filter_label, exact_label;
  std::vector<double> probability;
};

SplitScores scores_of(const PairDataset& dataset, const std::vector<double>& probability, Split split) {
  SplitScores scores;
  for (std::size_t i = 0; i < dataset.row_count(); ++i) {
    if (dataset.split[i] != split) continue;
    scores.filter_label.push_back(dataset.filter_label[i]);
    scores.exact_label.push_back(dataset.exact_label[i]);
    scores.probability.push_back(probability[i]);
  }
  return scores;
}

void write_curve(const std::vector<NeuronCountResult>& curve, const std::string& out_dir) {
  const std::string csv = out_dir + "/neurons.csv";
  std::ofstream file(csv);
  file.precision(17);
  file << "neurons,training_error,selection_error,best_trial\n";
  render::LineSeries training{"training", {}, {}}, selection{"selection", {}, {}};
  for (const NeuronCountResult& r : curve) {
    file << r.neurons << ',' << r.training_error << ',' << r.selection_error << ',' << r.best_trial << '\n';
    training.x.push_back(static_cast<double>(r.neurons));
    training.y.push_back(r.training_error);
    selection.x.push_back(static_cast<double>(r.neurons));
    selection.y.push_back(r.selection_error);
  }
  if (!file.flush()) throw std::runtime_error(csv + ": write failed");
  render::LineChart chart;
  chart.text = {"Error per hidden-neuron count (incremental order selection)", "hidden neurons",
                "normalized squared error", ""};
  chart.series = {training, selection};
  chart.markers = true;  // y from the data: the curve is nearly flat, an axis from 0 would hide it
  render::write_line_chart_svg(out_dir + "/neurons.svg", chart);
}

}  // namespace

TrainingReport train_pair_network(const PairDataset& dataset, const TrainingSettings& settings,
                                  const std::string& out_dir, const std::string& dataset_name,
                                  const TrainingProgress& progress) {
  check_dataset(dataset, settings);
  const std::vector<std::size_t> columns = varying_feature_columns(dataset);
  if (columns.empty()) throw std::invalid_argument("every feature column is constant: nothing to learn from");
  const backend::OpennnData data = opennn_data(dataset, columns);

  TrainingReport report;
  std::optional<backend::OpennnTraining> best;
  const std::size_t total = settings.max_neurons * settings.trials;
  for (std::size_t neurons = 1; neurons <= settings.max_neurons; ++neurons) {
    NeuronCountResult step;
    step.neurons = neurons;
    step.selection_error = std::numeric_limits<double>::infinity();
    for (std::size_t trial = 0; trial < settings.trials; ++trial) {
      if (progress) progress((neurons - 1) * settings.trials + trial, total, neurons);
      backend::OpennnTrainSettings train;
      train.hidden_neurons = neurons;
      train.seed = trial_seed(settings.seed, neurons, trial);
      train.max_epochs = settings.max_epochs;
      train.decision_threshold = settings.decision_threshold;
      backend::OpennnTraining run = backend::OpennnTraining::run(data, train);
      if (run.selection_error < step.selection_error) {
        step.selection_error = run.selection_error;
        step.training_error = run.training_error;
        step.best_trial = trial;
      }
      if (!best || run.selection_error < best->selection_error) best = std::move(run);
    }
    report.curve.push_back(step);
  }
  if (progress) progress(total, total, settings.max_neurons);

  // Written under temporary names and renamed at the end, so that a failed run leaves a model already in out_dir
  // whole (its network.xml and card.json belong together).
  std::filesystem::create_directories(out_dir);
  const std::string network_path = out_dir + "/network.xml";
  const std::string network_part = network_path + ".part", card_part = out_dir + "/card.json.part";
  best->network.save(network_part);
  // The runtime path: read back the file as the library will, so the card describes exactly what was saved.
  NetworkWeights weights;
  try {
    weights = read_network_weights(network_part);
  } catch (const std::runtime_error& e) {
    std::filesystem::remove(network_part);
    throw std::runtime_error(std::string("training gave an unusable network (") + e.what() +
                             "); features of extreme magnitude overflow the scaling layer: rescale or drop them. "
                             "Nothing was written to " + out_dir);
  }
  const std::vector<std::string> features = pair_feature_names(FeatureSettings{settings.feature_count});
  const PairClassifier classifier(std::move(weights), OperatingPoint{0.0, settings.decision_threshold}, features,
                                  network_path);
  PairFeatureBatch batch;
  batch.resize(dataset.row_count(), dataset.feature_count());
  for (std::size_t i = 0; i < dataset.row_count(); ++i)
    for (std::size_t f = 0; f < dataset.feature_count(); ++f) batch.column(f)[i] = dataset.row(i)[f];
  std::vector<double> probability(dataset.row_count());
  classifier.probabilities(batch, probability.data());

  ModelCard& card = report.card;
  card.feature_version = kPairFeatureVersion;
  card.feature_count = settings.feature_count;
  card.features = dataset.feature_names;
  card.inputs = data.input_names;
  for (std::size_t f = 0; f < dataset.feature_count(); ++f)
    if (std::find(columns.begin(), columns.end(), f) == columns.end()) card.dropped_columns.push_back(dataset.feature_names[f]);
  card.dataset = dataset_name;
  const ClassBalance balance = class_balance(dataset);
  card.rows_training = balance.rows[0];
  card.rows_selection = balance.rows[1];
  card.rows_testing = balance.rows[2];
  card.hidden_neurons = classifier.weights().layers.front().outputs;
  card.max_neurons = settings.max_neurons;
  card.trials = settings.trials;
  card.seed = settings.seed;
  card.decision_threshold = settings.decision_threshold;
  card.drop_below = choose_drop_below(dataset, probability, settings);
  card.keep_from = choose_keep_from(dataset, probability, settings);

  const SplitScores selection = scores_of(dataset, probability, Split::Selection);
  const SplitScores testing = scores_of(dataset, probability, Split::Testing);
  report.selection_confusion = confusion_matrix(selection.filter_label.data(), selection.probability.data(),
                                                selection.probability.size(), settings.decision_threshold);
  report.testing_confusion = confusion_matrix(testing.filter_label.data(), testing.probability.data(),
                                              testing.probability.size(), settings.decision_threshold);
  card.metrics.emplace_back("training_error", report.curve[card.hidden_neurons - 1].training_error);
  card.metrics.emplace_back("selection_error", report.curve[card.hidden_neurons - 1].selection_error);
  card.metrics.emplace_back("selection_accuracy", report.selection_confusion.accuracy());
  if (!testing.probability.empty()) {  // no testing rows: no testing metrics (not zeros)
    card.metrics.emplace_back("testing_accuracy", report.testing_confusion.accuracy());
    const ConfusionMatrix testing_exact = confusion_matrix(testing.exact_label.data(), testing.probability.data(),
                                                           testing.probability.size(), card.drop_below);
    card.metrics.emplace_back("testing_real_collisions",
                              static_cast<double>(testing_exact.true_positive + testing_exact.false_negative));
    card.metrics.emplace_back("testing_real_collisions_dropped", static_cast<double>(testing_exact.false_negative));
  }
  const std::size_t testing_positive = report.testing_confusion.true_positive + report.testing_confusion.false_negative;
  if (testing_positive > 0 && testing_positive < testing.probability.size()) {
    report.testing_auc = area_under_curve(
        roc_curve(testing.filter_label.data(), testing.probability.data(), testing.probability.size()));
    card.metrics.emplace_back("testing_auc", report.testing_auc);
  }
  try {
    write_model_card(card, card_part);
  } catch (...) {
    std::filesystem::remove(network_part);
    throw;
  }
  std::filesystem::rename(network_part, network_path);
  std::filesystem::rename(card_part, out_dir + "/card.json");
  write_curve(report.curve, out_dir);
  return report;
}

}  // namespace clothcd::learning
