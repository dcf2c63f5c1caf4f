// `clothcd train DATASET.csv --out models/NAME`: the paper's network trained by OpenNN with incremental neuron
// selection; writes network.xml, card.json, neurons.csv and neurons.svg into the output directory.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

#include "clothcd/culling/pair_classifier.hpp"
#include "clothcd/learning/network_training.hpp"
#include "clothcd/learning/pair_dataset.hpp"
#include "clothcd/learning/random_pairs.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct TrainOptions {
  std::string dataset;
  std::string out;
  double rebalance = 0.0;
  std::size_t random_pairs = 0;
  learning::TrainingSettings settings;
  bool json = false;
  bool quiet = false;
};

void run_train(const TrainOptions& options) {
  // Checked before any work, which can take minutes.
  create_output_folder(options.out, "--out");
  if (options.random_pairs > 0) check_output_file(options.dataset, "DATASET", {".csv"});
  if (options.random_pairs > 0) {
    learning::RandomPairSettings random;
    random.rows = options.random_pairs;
    random.seed = options.settings.seed;
    if (!options.quiet) std::cerr << "writing " << random.rows << " labelled random pairs to " << options.dataset << '\n';
    learning::write_pair_dataset_csv(learning::make_random_pair_dataset(random), options.dataset);
  }
  learning::PairDataset dataset = learning::read_pair_dataset_csv(options.dataset);
  if (!(options.rebalance >= 0.0)) throw std::invalid_argument("--rebalance must be >= 0 (0: off)");
  if (options.rebalance > 0.0)
    dataset = learning::rebalance_training_rows(dataset, options.rebalance, options.settings.seed);
  learning::TrainingSettings settings = options.settings;
  settings.feature_count = dataset.feature_count();
  const learning::ClassBalance balance = learning::class_balance(dataset);
  Progress progress("training", "trainings", options.quiet);
  const learning::TrainingReport report = learning::train_pair_network(
      dataset, settings, options.out, options.dataset, [&](std::size_t done, std::size_t total, std::size_t neurons) {
        progress.update(done, total, "hidden neurons " + std::to_string(neurons));
      });
  const learning::ModelCard& card = report.card;
  if (options.json) {
    Json out = json_report("train");
    out["dataset"] = options.dataset;
    out["out"] = options.out;
    out["splits"] = class_balance_json(balance);
    Json curve = Json::array();
    for (const learning::NeuronCountResult& r : report.curve)
      curve.push_back({{"neurons", r.neurons}, {"training_error", r.training_error},
                       {"selection_error", r.selection_error}});
    out["neuron_curve"] = curve;
    out["hidden_neurons"] = card.hidden_neurons;
    out["dropped_columns"] = card.dropped_columns;
    out["selection_confusion"] = confusion_json(report.selection_confusion);
    out["selection_accuracy"] = report.selection_confusion.accuracy();
    out["testing_confusion"] = confusion_json(report.testing_confusion);
    out["testing_accuracy"] = card.rows_testing > 0 ? Json(report.testing_confusion.accuracy()) : Json(nullptr);
    out["testing_auc"] = report.testing_auc;  // NaN (undefined) is written as null
    out["decision_threshold"] = card.decision_threshold;
    out["drop_below"] = card.drop_below;
    out["keep_from"] = card.keep_from;
    out["files"] = {"network.xml", "card.json", "neurons.csv", "neurons.svg"};
    print_json(out);
    return;
  }
  std::cout << "data set: " << options.dataset << "\n";
  for (int s = 0; s < 3; ++s)
    std::cout << "  " << std::setw(9) << learning::split_name(static_cast<learning::Split>(s)) << ": "
              << balance.rows[s] << " rows, filter label 1: " << balance.filter_positive[s]
              << ", exact label 1: " << balance.exact_positive[s] << '\n';
  std::cout << "neurons  training_error  selection_error\n";
  for (const learning::NeuronCountResult& r : report.curve)
    std::cout << std::setw(7) << r.neurons << "  " << std::setw(14) << r.training_error << "  " << std::setw(15)
              << r.selection_error << '\n';
  std::cout << "chosen hidden neurons: " << card.hidden_neurons << "\n"
            << "dropped constant columns: " << card.dropped_columns.size() << "\n"
            << "selection accuracy: " << report.selection_confusion.accuracy() << "\n"
            << "testing accuracy: "
            << measure_text(card.rows_testing > 0, report.testing_confusion.accuracy(), "- (no testing rows)")
            << "  AUC: "
            << measure_text(!std::isnan(report.testing_auc), report.testing_auc,
                            "- (undefined: no testing rows or one class)")
            << "\n"
            << "operating point: drop below " << card.drop_below << ", keep from "
            << card.keep_from << " (decision threshold " << card.decision_threshold << ")\n"
            << "wrote " << options.out << "/{network.xml,card.json,neurons.csv,neurons.svg}\n";
}

}  // namespace

void add_train_command(CLI::App& app) {
  auto* command = app.add_subcommand("train", "Train the pair network (OpenNN, quasi-Newton, incremental neuron selection)");
  auto options = std::make_shared<TrainOptions>();
  command->add_option("DATASET", options->dataset, "Pair data set CSV (datasets/README.md)")->required();
  command->add_option("--out", options->out, "Output model directory, e.g. models/NAME")->required();
  // Ranges on the text (before the conversion, where "-1" would wrap around an unsigned type).
  command->add_option("--max-neurons", options->settings.max_neurons, "Search 1..N hidden neurons")
      ->check(CLI::Range(std::size_t{1}, learning::kMaxLayerNeurons))->capture_default_str();
  command->add_option("--trials", options->settings.trials, "Trainings per neuron count")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  command->add_option("--seed", options->settings.seed, "Seed (same seed, same model)")
      ->check(kSeedNumber)->capture_default_str();
  command->add_option("--max-epochs", options->settings.max_epochs, "Quasi-Newton iterations per training")
      ->check(CLI::Range(1, 1000000))->capture_default_str();
  command->add_option("--threshold", options->settings.decision_threshold, "Decision threshold of the binary layer")
      ->capture_default_str();
  command->add_option("--rebalance", options->rebalance,
                      "Keep at most RATIO x the minority class of the training rows (0: off)")
      ->check(CLI::Range(0.0, 1e6))->capture_default_str();
  command->add_option("--random-pairs", options->random_pairs,
                      "First write N seeded random CCD pairs (labelled by the CCD filters and exact CCD) to DATASET")
      ->check(CLI::Range(1, 100000000));
  add_json_flag(*command, options->json);
  add_quiet_flag(*command, options->quiet);
  command->callback([options] { run_train(*options); });
}

}  // namespace clothcd::cli
