// `clothcd evaluate MODEL DATASET`: confusion matrix, rates, ROC (CSV + PNG) and AUC on the testing split, real
// collisions the network would drop, and inference speed against OpenNN.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "clothcd/learning/model_evaluation.hpp"
#include "clothcd/learning/pair_dataset.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct EvaluateOptions {
  std::string model;
  std::string dataset;
  std::string split = "testing";
  std::string roc;
  bool json = false;
};

// The ROC files' prefix: --roc, else MODEL_DIR/roc.
std::string roc_prefix(const EvaluateOptions& options) {
  if (!options.roc.empty()) return options.roc;
  const std::filesystem::path model(options.model);
  return ((std::filesystem::is_directory(model) ? model : model.parent_path()) / "roc").string();
}

void run_evaluate(const EvaluateOptions& options) {
  const std::string prefix = roc_prefix(options);
  // Before the evaluation (a missing model is reported by the evaluation itself).
  if (!options.roc.empty() || std::filesystem::exists(options.model)) check_output_file(prefix + ".csv", "--roc");
  const learning::PairDataset dataset = learning::read_pair_dataset_csv(options.dataset);
  learning::EvaluationSettings settings;
  if (options.split == "training") settings.split = learning::Split::Training;
  if (options.split == "selection") settings.split = learning::Split::Selection;
  if (options.split == "testing") settings.split = learning::Split::Testing;
  const learning::EvaluationReport r = learning::evaluate_pair_model(options.model, dataset, settings);
  const learning::ConfusionMatrix& c = r.filter_confusion;
  if (!r.roc.empty()) learning::write_roc_curve(r.roc, r.auc, prefix);
  if (options.json) {
    Json out = json_report("evaluate");
    out["model"] = options.model;
    out["dataset"] = options.dataset;
    out["split"] = options.split;
    out["rows"] = r.rows;
    out["decision_threshold"] = r.decision_threshold;
    out["filter_confusion"] = confusion_json(c);
    const auto defined = [](bool has_data, double value) { return has_data ? Json(value) : Json(nullptr); };
    out["accuracy"] = c.accuracy();
    out["error_rate"] = c.error_rate();
    out["sensitivity"] = defined(c.true_positive + c.false_negative > 0, c.sensitivity());
    out["specificity"] = defined(c.true_negative + c.false_positive > 0, c.specificity());
    out["auc"] = defined(!r.roc.empty(), r.auc);
    out["drop_below"] = r.drop_below;
    out["keep_from"] = r.keep_from;
    out["real_collisions"] = r.real_collisions;
    out["real_collisions_dropped"] = r.real_collisions_dropped;
    out["real_collisions_below_threshold"] = r.real_collisions_below_threshold;
    out["decisions"] = {{"dropped", r.dropped}, {"checked", r.checked}, {"kept", r.kept},
                        {"removable_kept", r.removable_kept}};
    out["network_removal_rate"] = r.network_removal_rate;
    out["filter_removal_rate"] = r.filter_removal_rate;
    out["ns_per_row"] = r.ns_per_row;
    out["opennn_batch_ns_per_row"] = r.opennn_batch_ns_per_row;
    out["opennn_single_ns_per_row"] = r.opennn_single_ns_per_row;
    out["max_difference_vs_opennn"] = r.max_difference_vs_opennn;
    out["roc_files"] = r.roc.empty() ? Json::array() : Json::array({prefix + ".csv", prefix + ".svg"});
    print_json(out);
    return;
  }
  std::cout << "model: " << options.model << "\ndata set: " << options.dataset << " (" << options.split << ", "
            << r.rows << " rows)\n"
            << "against the filter label (threshold " << r.decision_threshold << "):\n"
            << "                  predicted 1  predicted 0\n"
            << "  filter label 1  " << c.true_positive << "  " << c.false_negative << "\n"
            << "  filter label 0  " << c.false_positive << "  " << c.true_negative << "\n"
            << "  accuracy " << c.accuracy() << "  error rate " << c.error_rate() << "  sensitivity "
            << measure_text(c.true_positive + c.false_negative > 0, c.sensitivity(), "- (no label 1)") << "  specificity "
            << measure_text(c.true_negative + c.false_positive > 0, c.specificity(), "- (no label 0)") << "  AUC "
            << measure_text(!r.roc.empty(), r.auc, "- (undefined: one class)") << "\n"
            << "against the exact label (drop below " << r.drop_below << "):\n"
            << "  real collisions " << r.real_collisions << ", dropped by the network alone " << r.real_collisions_dropped
            << " (below the decision threshold: " << r.real_collisions_below_threshold
            << "; the detector's filters check every drop)\n"
            << "decisions: dropped " << r.dropped << ", checked by the filters " << r.checked << ", kept " << r.kept
            << " (from " << r.keep_from << "; of them the filters would remove " << r.removable_kept << ")"
            << "\nremoval rate: network culler (network, filters on every pair not kept) " << r.network_removal_rate << ", combined filters "
            << r.filter_removal_rate << "\n"
            << "inference per row: clothcd " << r.ns_per_row << " ns, OpenNN batch " << r.opennn_batch_ns_per_row
            << " ns, OpenNN one row " << r.opennn_single_ns_per_row << " ns; max |clothcd - OpenNN| "
            << r.max_difference_vs_opennn << "\n";
  if (!r.roc.empty()) std::cout << "wrote " << prefix << ".csv and " << prefix << ".svg\n";
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto* command = app.add_subcommand("evaluate", "Evaluate a pair network: confusion, ROC/AUC, real collisions dropped");
  auto options = std::make_shared<EvaluateOptions>();
  command->add_option("MODEL", options->model, "Model directory (or its network.xml)")->required();
  command->add_option("DATASET", options->dataset, "Pair data set CSV")->required();
  command->add_option("--split", options->split, "Split of the data set to evaluate on")
      ->check(CLI::IsMember({"training", "selection", "testing"}))
      ->capture_default_str();
  command->add_option("--roc", options->roc, "Prefix of the ROC CSV/SVG (default MODEL_DIR/roc)")
      ->check(CLI::Validator(
          [](std::string& text) {
            const std::filesystem::path path(text);
            return text.empty() || !path.has_filename() || std::filesystem::is_directory(path)
                       ? std::string("must be a file name prefix (PREFIX.csv and PREFIX.svg are written), not a folder")
                       : std::string();
          },
          "PREFIX"));
  add_json_flag(*command, options->json);
  command->callback([options] { run_evaluate(*options); });
}

}  // namespace clothcd::cli
