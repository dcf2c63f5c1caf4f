// Confusion matrix, rates, ROC curve and AUC (Jin et al., section 4.3). The ROC is built by one sort of the scores,
// O(n log n), instead of OpenNN's O(positives x negatives) pair count; rows with equal scores form one step, so the
// trapezoid area equals the Mann-Whitney statistic with ties counted one half.
#include "clothcd/learning/classification_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace clothcd::learning {

double ConfusionMatrix::accuracy() const {
  return total() == 0 ? 0.0 : static_cast<double>(true_positive + true_negative) / static_cast<double>(total());
}

double ConfusionMatrix::error_rate() const { return total() == 0 ? 0.0 : 1.0 - accuracy(); }

double ConfusionMatrix::sensitivity() const {
  const std::size_t positives = true_positive + false_negative;
  return positives == 0 ? 1.0 : static_cast<double>(true_positive) / static_cast<double>(positives);
}

double ConfusionMatrix::specificity() const {
  const std::size_t negatives = true_negative + false_positive;
  return negatives == 0 ? 1.0 : static_cast<double>(true_negative) / static_cast<double>(negatives);
}

ConfusionMatrix confusion_matrix(const int* labels, const double* scores, std::size_t count, double threshold) {
  ConfusionMatrix matrix;
  for (std::size_t i = 0; i < count; ++i) {
    const bool predicted = !(scores[i] < threshold);
    if (labels[i] == 1) (predicted ? matrix.true_positive : matrix.false_negative)++;
    else (predicted ? matrix.false_positive : matrix.true_negative)++;
  }
  return matrix;
}

std::vector<RocPoint> roc_curve(const int* labels, const double* scores, std::size_t count) {
  std::size_t positives = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (std::isnan(scores[i])) throw std::invalid_argument("ROC curve: NaN score");
    positives += labels[i] == 1;
  }
  const std::size_t negatives = count - positives;
  if (positives == 0 || negatives == 0) throw std::invalid_argument("ROC curve: needs both positive and negative rows");
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  std::vector<RocPoint> curve{{std::numeric_limits<double>::infinity(), 0.0, 0.0}};
  std::size_t true_positive = 0, false_positive = 0;
  for (std::size_t k = 0; k < count;) {
    const double score = scores[order[k]];
    for (; k < count && scores[order[k]] == score; ++k) (labels[order[k]] == 1 ? true_positive : false_positive)++;
    curve.push_back({score, static_cast<double>(false_positive) / static_cast<double>(negatives),
                     static_cast<double>(true_positive) / static_cast<double>(positives)});
  }
  return curve;
}

double area_under_curve(const std::vector<RocPoint>& curve) {
  double area = 0.0;
  for (std::size_t k = 1; k < curve.size(); ++k)
    area += (curve[k].false_positive_rate - curve[k - 1].false_positive_rate) *
            0.5 * (curve[k].true_positive_rate + curve[k - 1].true_positive_rate);
  return area;
}

}  // namespace clothcd::learning
