// Evaluation of the pair network (Jin et al., section 4.3: confusion matrix, ROC curve of Figure 13, AUC), extended
// with the safety count the paper does not give: real collisions (exact CCD) that the operating point would drop.
#include "clothcd/learning/model_evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "clothcd/culling/pair_classifier.hpp"
#include "clothcd/render/svg_chart.hpp"
#include "learning/opennn_backend.hpp"

namespace clothcd::learning {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ns(Clock::time_point since) {
  return std::chrono::duration<double, std::nano>(Clock::now() - since).count();
}

std::string network_file(const std::string& model) {
  std::error_code error;
  return std::filesystem::is_directory(model, error) ? model + "/network.xml" : model;
}

}  // namespace

EvaluationReport evaluate_pair_model(const std::string& model, const PairDataset& dataset,
                                     const EvaluationSettings& settings) {
  FeatureSettings features;
  features.count = dataset.feature_count();
  if (dataset.feature_names != pair_feature_names(features))
    throw std::runtime_error("the data set's feature columns are not the pair features of definition version " +
                             std::to_string(kPairFeatureVersion));
  const PairClassifier classifier = PairClassifier::load(model, features);

  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < dataset.row_count(); ++i)
    if (dataset.split[i] == settings.split) rows.push_back(i);
  if (rows.empty()) throw std::invalid_argument(std::string("the data set has no ") + split_name(settings.split) + " rows");

  PairFeatureBatch batch;
  batch.resize(rows.size(), dataset.feature_count());
  std::vector<int> filter_label, exact_label;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t f = 0; f < dataset.feature_count(); ++f) batch.column(f)[r] = dataset.row(rows[r])[f];
    filter_label.push_back(dataset.filter_label[rows[r]]);
    exact_label.push_back(dataset.exact_label[rows[r]]);
  }
  std::vector<double> probability(rows.size());
  std::vector<PairDecision> decision(rows.size());
  classifier.probabilities(batch, probability.data());
  classifier.decide(batch, decision.data());

  EvaluationReport report;
  report.rows = rows.size();
  report.decision_threshold = classifier.operating_point().decision_threshold;
  report.drop_below = classifier.operating_point().drop_below;
  report.keep_from = classifier.operating_point().keep_from;
  report.filter_confusion = confusion_matrix(filter_label.data(), probability.data(), rows.size(), report.decision_threshold);
  const std::size_t positives = report.filter_confusion.true_positive + report.filter_confusion.false_negative;
  if (positives > 0 && positives < rows.size()) {
    report.roc = roc_curve(filter_label.data(), probability.data(), rows.size());
    report.auc = area_under_curve(report.roc);
  }
  std::size_t removed = 0, filter_removed = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const bool real = exact_label[r] == 1;
    report.real_collisions += real;
    report.real_collisions_dropped += real && decision[r] == PairDecision::Drop;
    report.real_collisions_below_threshold += real && probability[r] < report.decision_threshold;
    report.dropped += decision[r] == PairDecision::Drop;
    report.checked += decision[r] == PairDecision::Check;
    report.kept += decision[r] == PairDecision::Keep;
    report.removable_kept += decision[r] == PairDecision::Keep && filter_label[r] == 0;
    filter_removed += filter_label[r] == 0;
    removed += decision[r] != PairDecision::Keep && filter_label[r] == 0;
  }
  report.filter_removal_rate = static_cast<double>(filter_removed) / static_cast<double>(rows.size());
  report.network_removal_rate = static_cast<double>(removed) / static_cast<double>(rows.size());

  // OpenNN on the same rows: agreement of the two forward passes and the speed of each.
  const std::size_t inputs = classifier.weights().input_count();
  std::vector<std::size_t> columns;
  for (const std::string& name : classifier.weights().input_names)
    columns.push_back(static_cast<std::size_t>(
        std::find(dataset.feature_names.begin(), dataset.feature_names.end(), name) - dataset.feature_names.begin()));
  std::vector<double> input_rows;
  input_rows.reserve(rows.size() * inputs);
  for (const std::size_t i : rows)
    for (const std::size_t c : columns) input_rows.push_back(dataset.row(i)[c]);
  const backend::OpennnNetwork opennn = backend::OpennnNetwork::load(network_file(model));
  Clock::time_point start = Clock::now();
  const std::vector<double> opennn_probability = opennn.outputs(input_rows, true);
  report.opennn_batch_ns_per_row = elapsed_ns(start) / static_cast<double>(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    report.max_difference_vs_opennn =
        std::max(report.max_difference_vs_opennn, std::abs(opennn_probability[r] - probability[r]));
  if (settings.time_inference) {
    const std::size_t single = std::min<std::size_t>(rows.size(), 2000);
    start = Clock::now();
    for (std::size_t r = 0; r < single; ++r) {
      const std::vector<double> one(input_rows.begin() + static_cast<long>(r * inputs),
                                    input_rows.begin() + static_cast<long>((r + 1) * inputs));
      (void)opennn.outputs(one, true);
    }
    report.opennn_single_ns_per_row = elapsed_ns(start) / static_cast<double>(single);
    std::size_t repeats = 0;
    start = Clock::now();
    do {
      classifier.probabilities(batch, probability.data());
      ++repeats;
    } while (elapsed_ns(start) < 2e8 && repeats < 1000);
    report.ns_per_row = elapsed_ns(start) / static_cast<double>(repeats * rows.size());
  }
  return report;
}

void write_roc_curve(const std::vector<RocPoint>& roc, double auc, const std::string& out_prefix) {
  const std::string csv = out_prefix + ".csv";
  std::ofstream file(csv);
  if (!file) throw std::runtime_error(csv + ": cannot open for writing");
  file.precision(17);
  file << "threshold,false_positive_rate,true_positive_rate\n";
  render::LineSeries series{"ROC", {}, {}};
  for (const RocPoint& p : roc) {
    file << p.threshold << ',' << p.false_positive_rate << ',' << p.true_positive_rate << '\n';
    series.x.push_back(p.false_positive_rate);
    series.y.push_back(p.true_positive_rate);
  }
  if (!file.flush()) throw std::runtime_error(csv + ": write failed");
  char note[32];
  std::snprintf(note, sizeof note, "AUC %.5f", auc);
  render::LineChart chart;
  chart.text = {"ROC of the pair network against the filter label", "false positive rate",
                "true positive rate", note};
  chart.series = {series};
  chart.x = chart.y = {0.0, 1.0};
  chart.diagonal = true;
  render::write_line_chart_svg(out_prefix + ".svg", chart);
}

}  // namespace clothcd::learning
