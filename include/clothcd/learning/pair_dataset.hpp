#pragma once
/// @file
/// Labelled CCD pairs for training and evaluating the pair network (Jin et al., section 3.3.1 (1)): one row per
/// candidate pair with its feature vector, the paper's filter label, the exact CCD label, the pair type, the scene and the
/// training/selection/testing split (60/20/20 from a seed). Read and written as CSV (datasets/README.md).

#include <cstddef>
#include <string>
#include <vector>

#include "clothcd/culling/pair_features.hpp"

namespace clothcd::learning {

/// Which subset a row belongs to.
enum class Split : unsigned char { Training, Selection, Testing };

/// "training", "selection" or "testing".
[[nodiscard]] const char* split_name(Split split);

/// One row to append: `features` points at feature_names.size() values.
struct PairRow {
  const double* features = nullptr;  ///< The feature vector (finite values).
  int filter_label = 1;              ///< 0 when the combined algebraic + projection filters remove the pair, else 1.
  int exact_label = 1;               ///< 1 when the exact CCD finds a collision in the step, else 0.
  PairKind type = PairKind::VertexFace;
  std::string scene;                 ///< Free text naming the scene the pair came from (no comma, quote or newline).
  Split split = Split::Training;     ///< Usually set afterwards by assign_splits.
};

/// Column store of labelled pairs.
struct PairDataset {
  std::vector<std::string> feature_names;  ///< Column names of the features, in order.
  std::vector<double> features;            ///< row_count() x feature_names.size(), row-major.
  std::vector<int> filter_label;           ///< Per row, 0 or 1 (see PairRow).
  std::vector<int> exact_label;            ///< Per row, 0 or 1 (see PairRow).
  std::vector<PairKind> type;              ///< Per row.
  std::vector<std::string> scene;          ///< Per row.
  std::vector<Split> split;                ///< Per row.

  /// Number of rows.
  [[nodiscard]] std::size_t row_count() const { return filter_label.size(); }
  /// Number of feature columns.
  [[nodiscard]] std::size_t feature_count() const { return feature_names.size(); }
  /// Pointer to the feature_count() features of row `row`.
  [[nodiscard]] const double* row(std::size_t row) const { return features.data() + row * feature_count(); }
  /// Appends a row; throws std::invalid_argument on non-finite features, labels other than 0/1 or a bad scene name.
  void add_row(const PairRow& row);
};

/// Fractions of the split (the rest is testing) and the seed of the shuffle.
struct SplitSettings {
  double training = 0.6;   ///< Fraction of rows for training.
  double selection = 0.2;  ///< Fraction of rows for selection.
  unsigned long long seed = 1;
};

/// Assigns splits: a seeded Fisher-Yates shuffle (SplitMix64, identical on every platform), then the first
/// floor(training * n) rows train, the next floor(selection * n) select, the rest test.
void assign_splits(PairDataset& dataset, const SplitSettings& settings);

/// Writes the CSV: header `<features...>,filter_label,exact_label,type,scene,split`, numbers with 17 significant digits.
/// Throws std::runtime_error naming the file when it cannot be written.
void write_pair_dataset_csv(const PairDataset& dataset, const std::string& path);

/// Reads the CSV written by write_pair_dataset_csv. Every problem (missing file, missing label columns, wrong field
/// count, non-numeric or non-finite value, label not 0/1, unknown type or split) throws std::runtime_error naming the
/// file and line.
[[nodiscard]] PairDataset read_pair_dataset_csv(const std::string& path);

/// Indices of the feature columns that are not constant over all rows (OpenNN's min-max scaling breaks on constants).
[[nodiscard]] std::vector<std::size_t> varying_feature_columns(const PairDataset& dataset);

/// Rows per split and per label: what `clothcd train` and `evaluate` print as the class balance.
struct ClassBalance {
  std::size_t rows[3] = {0, 0, 0};             ///< Rows per Split.
  std::size_t filter_positive[3] = {0, 0, 0};  ///< Rows with filter_label 1 per Split.
  std::size_t exact_positive[3] = {0, 0, 0};   ///< Rows with exact_label 1 per Split.
};

/// Counts rows per split and label.
[[nodiscard]] ClassBalance class_balance(const PairDataset& dataset);

/// Re-balancing: keeps every row of the minority filter class of the training split and a seeded random sample of the
/// majority class `ratio` times the minority's size; selection and testing rows are untouched (they stay honest).
[[nodiscard]] PairDataset rebalance_training_rows(const PairDataset& dataset, double ratio, unsigned long long seed);

}  // namespace clothcd::learning
