// Metrics: the O(n log n) AUC against a brute-force pair count and against OpenNN's own AUC; confusion rates.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "clothcd/learning/classification_metrics.hpp"
#include "learning/opennn_backend.hpp"

using namespace clothcd::learning;

namespace {

// Mann-Whitney: the probability that a random positive scores above a random negative, ties one half.
double brute_force_auc(const std::vector<int>& labels, const std::vector<double>& scores) {
  double wins = 0.0, pairs = 0.0;
  for (std::size_t i = 0; i < labels.size(); ++i)
    for (std::size_t j = 0; j < labels.size(); ++j)
      if (labels[i] == 1 && labels[j] == 0) {
        pairs += 1.0;
        wins += scores[i] > scores[j] ? 1.0 : (scores[i] == scores[j] ? 0.5 : 0.0);
      }
  return wins / pairs;
}

}  // namespace

TEST_CASE("AUC equals the brute-force Mann-Whitney statistic, ties included", "[learning][metrics]") {
  std::mt19937_64 rng(8);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<int> labels;
    std::vector<double> scores;
    for (int i = 0; i < 300; ++i) {
      const int label = rng() % 3 == 0 ? 1 : 0;
      labels.push_back(label);
      scores.push_back(static_cast<double>(rng() % 20) / 20.0 + 0.1 * label);  // many ties
    }
    const std::vector<RocPoint> roc = roc_curve(labels.data(), scores.data(), labels.size());
    CHECK(roc.front().false_positive_rate == 0.0);
    CHECK(roc.back().true_positive_rate == 1.0);
    CHECK(roc.back().false_positive_rate == 1.0);
    CHECK(area_under_curve(roc) == Approx(brute_force_auc(labels, scores)).margin(1e-12));
  }
}

TEST_CASE("AUC agrees with OpenNN's on untied scores", "[learning][metrics][opennn]") {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<int> labels;
  std::vector<double> label_values, scores;
  for (int i = 0; i < 400; ++i) {
    const int label = rng() % 2;
    labels.push_back(label);
    label_values.push_back(label);
    scores.push_back(1.0 / (1.0 + std::exp(-(noise(rng) + 1.5 * label))));
  }
  const double ours = area_under_curve(roc_curve(labels.data(), scores.data(), labels.size()));
  CHECK(ours > 0.7);
  CHECK(ours == Approx(backend::opennn_area_under_curve(label_values, scores)).margin(1e-9));
}

TEST_CASE("confusion matrix and its rates", "[learning][metrics]") {
  const int labels[] = {1, 1, 1, 0, 0, 0, 0};
  const double scores[] = {0.9, 0.6, 0.2, 0.7, 0.1, 0.3, 0.5};
  const ConfusionMatrix m = confusion_matrix(labels, scores, 7, 0.5);
  CHECK(m.true_positive == 2);
  CHECK(m.false_negative == 1);
  CHECK(m.false_positive == 2);  // 0.7 and 0.5 (>= threshold predicts 1)
  CHECK(m.true_negative == 2);
  CHECK(m.accuracy() == Approx(4.0 / 7.0));
  CHECK(m.error_rate() == Approx(3.0 / 7.0));
  CHECK(m.sensitivity() == Approx(2.0 / 3.0));
  CHECK(m.specificity() == Approx(0.5));
  const int one_class[] = {1, 1};
  CHECK_THROWS_AS(roc_curve(one_class, scores, 2), std::invalid_argument);
}
