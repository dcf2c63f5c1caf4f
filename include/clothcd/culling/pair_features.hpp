#pragma once
/// @file
/// The feature vector of a CCD candidate pair: what the pair network sees (Jin et al., section 3.3.1: 15 inputs; the
/// paper does not name them, these are ours, documented one by one in datasets/README.md).
///
/// Every feature depends only on the eight positions (four points at the start and at the end of the step), is
/// invariant to translation and is scaled by the pair size L (the diagonal of the box around the eight positions), so
/// that scenes of any size look alike. Lengths are divided by L, the coplanarity cubic by L^3.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::learning {

/// "VF" (vertex-face) or "EE" (edge-edge). A pair's geometry is the CCD query of its eight positions (ccd::CcdQuery).
[[nodiscard]] const char* pair_kind_name(PairKind kind);

/// Number of features defined; FeatureSettings::count picks the first `count` of them.
inline constexpr std::size_t kMaxPairFeatures = 18;

/// Version of the feature definition; stored in model cards and checked when a model is loaded.
inline constexpr int kPairFeatureVersion = 1;

/// How many features to compute.
struct FeatureSettings {
  std::size_t count = 15;  ///< 1..kMaxPairFeatures; the paper uses 15.
};

/// Names of the first settings.count features, in order (throws std::invalid_argument for a bad count).
[[nodiscard]] std::vector<std::string> pair_feature_names(const FeatureSettings& settings);

/// Writes the first settings.count features of one pair to `out` (settings.count values). A pair of zero size (all
/// eight positions equal) gives all zeros; non-finite positions give non-finite features.
void compute_pair_features(const ccd::CcdQuery& pair, const FeatureSettings& settings, double* out);

/// Features of many pairs, structure of arrays: feature f of pair i at values[f * rows + i].
struct PairFeatureBatch {
  std::size_t rows = 0;        ///< Pairs.
  std::size_t features = 0;    ///< Features per pair.
  std::vector<double> values;  ///< features x rows.

  /// Sizes the batch (reuses the allocation when large enough).
  void resize(std::size_t new_rows, std::size_t new_features) {
    rows = new_rows;
    features = new_features;
    values.resize(rows * features);
  }
  /// The `rows` values of feature f.
  [[nodiscard]] const double* column(std::size_t f) const { return values.data() + f * rows; }
  /// The `rows` values of feature f.
  [[nodiscard]] double* column(std::size_t f) { return values.data() + f * rows; }
};

/// Computes the features of `count` pairs into `batch` (resized to count x settings.count).
void compute_pair_features(const ccd::CcdQuery* pairs, std::size_t count, const FeatureSettings& settings,
                           PairFeatureBatch& batch);

}  // namespace clothcd::learning
