#pragma once
/// @file
/// Binary classification metrics of the pair network: confusion matrix, accuracy, error rate, sensitivity,
/// specificity, ROC curve and its area (Jin et al., section 4.3, Figure 13). Label 1 = positive.

#include <cstddef>
#include <vector>

namespace clothcd::learning {

/// Counts of a binary classifier against 0/1 labels.
struct ConfusionMatrix {
  std::size_t true_positive = 0;   ///< Label 1, predicted 1.
  std::size_t false_negative = 0;  ///< Label 1, predicted 0.
  std::size_t false_positive = 0;  ///< Label 0, predicted 1.
  std::size_t true_negative = 0;   ///< Label 0, predicted 0.

  /// All counted rows.
  [[nodiscard]] std::size_t total() const { return true_positive + false_negative + false_positive + true_negative; }
  /// (TP + TN) / total, 0 when empty.
  [[nodiscard]] double accuracy() const;
  /// 1 - accuracy (0 when empty).
  [[nodiscard]] double error_rate() const;
  /// TP / (TP + FN), 1 when there is no positive.
  [[nodiscard]] double sensitivity() const;
  /// TN / (TN + FP), 1 when there is no negative.
  [[nodiscard]] double specificity() const;
};

/// Confusion matrix of "predict 1 when score >= threshold" over `count` rows (a NaN score predicts 1).
[[nodiscard]] ConfusionMatrix confusion_matrix(const int* labels, const double* scores, std::size_t count,
                                               double threshold);

/// One point of a ROC curve: predicting 1 when score >= threshold gives these rates.
struct RocPoint {
  double threshold = 0.0;            ///< Score threshold (+inf for the first point (0, 0)).
  double false_positive_rate = 0.0;  ///< FP / negatives.
  double true_positive_rate = 0.0;   ///< TP / positives.
};

/// ROC curve in O(n log n): one point per distinct score, from (0, 0) to (1, 1). Throws std::invalid_argument when a
/// class is missing or a score is NaN.
[[nodiscard]] std::vector<RocPoint> roc_curve(const int* labels, const double* scores, std::size_t count);

/// Area under a ROC curve by trapezoids (equal to the Mann-Whitney statistic with ties counted one half).
[[nodiscard]] double area_under_curve(const std::vector<RocPoint>& curve);

}  // namespace clothcd::learning
