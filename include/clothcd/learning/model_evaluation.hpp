#pragma once
/// @file
/// Evaluation of a trained pair network on one split of a data set (Jin et al., section 4.3, Figure 13): confusion
/// matrix, accuracy, error rate, sensitivity, specificity, ROC and AUC against the filter label, and the safety view
/// against the exact label (real collisions the network would drop), plus inference speed against OpenNN.

#include <cstddef>
#include <string>
#include <vector>

#include "clothcd/learning/classification_metrics.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::learning {

/// What to evaluate.
struct EvaluationSettings {
  Split split = Split::Testing;  ///< Rows to evaluate.
  bool time_inference = true;    ///< Also time clothcd's forward pass and OpenNN's calculate_outputs on these rows.
};

/// Results of `clothcd evaluate`.
struct EvaluationReport {
  std::size_t rows = 0;                          ///< Rows of the split.
  double decision_threshold = 0.5;               ///< From the model card.
  double drop_below = 0.0;                       ///< From the model card.
  double keep_from = 0.5;                        ///< From the model card.
  std::size_t removable_kept = 0;                ///< Rows with filter label 0 the network keeps (skip the filters).
  ConfusionMatrix filter_confusion;              ///< Against the filter label, positive = probability >= threshold.
  std::vector<RocPoint> roc;                     ///< Against the filter label (empty when a class is missing).
  double auc = 0.0;                              ///< Area under `roc` (0 when empty).
  std::size_t real_collisions = 0;               ///< Rows with exact label 1.
  std::size_t real_collisions_dropped = 0;       ///< ... of which the network alone drops (probability < drop_below).
  std::size_t real_collisions_below_threshold = 0;  ///< ... below the decision threshold (dropped if no check ran).
  std::size_t dropped = 0, checked = 0, kept = 0;   ///< Decisions (see PairDecision).
  double filter_removal_rate = 0.0;   ///< Fraction with filter label 0 (what the combined filters remove).
  /// Fraction the detector's culler removes: pairs the network does not keep and the filters remove (the filters
  /// check every pair the network drops, as NetworkCuller does).
  double network_removal_rate = 0.0;
  double max_difference_vs_opennn = 0.0;  ///< Largest |clothcd - OpenNN| probability over the rows.
  double ns_per_row = 0.0;                ///< clothcd's batched forward pass (features given).
  double opennn_batch_ns_per_row = 0.0;   ///< OpenNN calculate_outputs on all rows at once.
  double opennn_single_ns_per_row = 0.0;  ///< OpenNN calculate_outputs one row at a time.
};

/// Evaluates MODEL (directory or network.xml) on `dataset`, whose feature columns must be those of the model card.
/// Throws std::runtime_error for a bad model or a mismatching data set, std::invalid_argument for an empty split.
[[nodiscard]] EvaluationReport evaluate_pair_model(const std::string& model, const PairDataset& dataset,
                                                   const EvaluationSettings& settings = {});

/// Writes OUT_PREFIX.csv (threshold, false_positive_rate, true_positive_rate) and OUT_PREFIX.svg, the ROC curve
/// charted with its `auc` (EvaluationReport::auc).
void write_roc_curve(const std::vector<RocPoint>& roc, double auc, const std::string& out_prefix);

}  // namespace clothcd::learning
