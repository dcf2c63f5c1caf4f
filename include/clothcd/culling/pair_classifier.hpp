#pragma once
/// @file
/// The trained pair network at run time (Jin et al., section 3.3: the network culls CCD candidate pairs). It evaluates
/// the loaded weights itself, batched over structure-of-arrays features, never through OpenNN's per-row calls, and
/// decides conservatively: only pairs it is sure about are dropped, unsure ones go through the filters.

#include <cstddef>
#include <string>
#include <vector>

#include "clothcd/culling/model_card.hpp"
#include "clothcd/culling/network_weights.hpp"
#include "clothcd/culling/pair_features.hpp"

namespace clothcd::learning {

/// What to do with a candidate pair.
enum class PairDecision : unsigned char {
  Drop,   ///< The network is sure the pair cannot collide (probability < drop_below): skip it.
  Check,  ///< The network is not sure the filters keep the pair: run the exact filters.
  Keep,   ///< The network is sure the pair survives the filters (or its output is not finite): exact CCD.
};

/// Where to cut the network's probability that the pair survives the filters.
struct OperatingPoint {
  double drop_below = 0.0;          ///< Drop when probability < drop_below (0 never drops).
  double decision_threshold = 0.5;  ///< The binary layer's threshold: probability >= it predicts "the filters keep it".
  /// Check when drop_below <= probability < keep_from, else keep (skip the filters). At least decision_threshold;
  /// above 1 nothing is kept. Training sets it above every selection-split pair the filters remove, so that skipping
  /// the filters costs (almost) no removal. Left out of an initializer, it equals decision_threshold.
  double keep_from = decision_threshold;
};

/// Largest number of neurons per layer the batched forward pass supports.
inline constexpr std::size_t kMaxLayerNeurons = 64;

/// A loaded pair network with its operating point and its map from feature columns to network inputs.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class PairClassifier {
 public:
  /// Builds from weights; `feature_names` names the columns of the batches that will be passed (usually
  /// pair_feature_names(settings)); every network input must be one of them. Throws std::runtime_error "<context>: ..."
  /// on invalid weights, an unknown input name or layers wider than kMaxLayerNeurons.
  PairClassifier(NetworkWeights weights, const OperatingPoint& operating_point,
                 const std::vector<std::string>& feature_names, const std::string& context);

  /// Loads MODEL (a model directory holding network.xml and card.json, or the network.xml itself) for features computed
  /// with `settings`. Throws std::runtime_error naming the file for a missing, truncated or malformed model, NaN
  /// weights, a feature definition or count that differs from `settings`, or an input count that differs from the card.
  [[nodiscard]] static PairClassifier load(const std::string& model, const FeatureSettings& settings = {});

  /// Probability per row that the pair survives the filters; `out` holds batch.rows values. The batch's columns must
  /// be the feature_names given at construction. No allocation.
  void probabilities(const PairFeatureBatch& batch, double* out) const;

  /// Decision per row (`out` holds batch.rows values). No allocation.
  void decide(const PairFeatureBatch& batch, PairDecision* out) const;

  /// Decision for one probability.
  [[nodiscard]] PairDecision decide(double probability) const {
    if (probability < operating_point_.drop_below) return PairDecision::Drop;
    if (probability < operating_point_.keep_from) return PairDecision::Check;
    return PairDecision::Keep;
  }

  /// The weights evaluated.
  [[nodiscard]] const NetworkWeights& weights() const { return weights_; }
  /// The operating point.
  [[nodiscard]] const OperatingPoint& operating_point() const { return operating_point_; }
  /// Sets the operating point (0 <= drop_below <= decision_threshold <= 1, decision_threshold <= keep_from, all
  /// finite; throws std::invalid_argument).
  void set_operating_point(const OperatingPoint& operating_point);

 private:
  NetworkWeights weights_;
  OperatingPoint operating_point_;
  std::vector<std::size_t> input_columns_;  // batch column of each network input
  std::size_t feature_count_ = 0;
};

/// Reference forward pass of one row of network inputs (already selected, input order), written as plainly as
/// possible: the slow obviously-correct twin of PairClassifier::probabilities.
[[nodiscard]] double reference_probability(const NetworkWeights& weights, const double* inputs);

}  // namespace clothcd::learning
