// Labelled pair data sets (Jin et al., section 3.3.1 (1)): rows labelled 0 when the filters remove the pair, 1
// otherwise, split 60/20/20 into training, selection and testing. CSV layout in datasets/README.md.
#include "clothcd/learning/pair_dataset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "learning/split_mix64.hpp"

namespace clothcd::learning {
namespace {

const char* const kLabelColumns[] = {"filter_label", "exact_label", "type", "scene", "split"};

void seeded_shuffle(std::vector<std::size_t>& order, unsigned long long seed) {
  SplitMix64 rng{seed};
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.next() % i]);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem) {
  throw std::runtime_error(path + ":" + std::to_string(line) + ": " + problem);
}

double parse_number(const std::string& text, const std::string& path, std::size_t line, const std::string& column) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
    fail(path, line, "column '" + column + "': '" + text + "' is not a finite number");
  return value;
}

int parse_label(const std::string& text, const std::string& path, std::size_t line, const std::string& column) {
  if (text != "0" && text != "1") fail(path, line, "column '" + column + "': label '" + text + "' is not 0 or 1");
  return text == "1" ? 1 : 0;
}

void append_row(PairDataset& into, const PairDataset& from, std::size_t row) {
  into.features.insert(into.features.end(), from.row(row), from.row(row) + from.feature_count());
  into.filter_label.push_back(from.filter_label[row]);
  into.exact_label.push_back(from.exact_label[row]);
  into.type.push_back(from.type[row]);
  into.scene.push_back(from.scene[row]);
  into.split.push_back(from.split[row]);
}

}  // namespace

const char* split_name(Split split) {
  switch (split) {
    case Split::Training: return "training";
    case Split::Selection: return "selection";
    case Split::Testing: return "testing";
  }
  return "?";
}

void PairDataset::add_row(const PairRow& row) {
  for (std::size_t f = 0; f < feature_count(); ++f)
    if (!std::isfinite(row.features[f]))
      throw std::invalid_argument("pair data set: feature '" + feature_names[f] + "' is not finite");
  if ((row.filter_label != 0 && row.filter_label != 1) || (row.exact_label != 0 && row.exact_label != 1))
    throw std::invalid_argument("pair data set: labels must be 0 or 1");
  if (row.scene.find_first_of(",\"\n\r") != std::string::npos)
    throw std::invalid_argument("pair data set: scene name '" + row.scene + "' holds a comma, quote or newline");
  features.insert(features.end(), row.features, row.features + feature_count());
  filter_label.push_back(row.filter_label);
  exact_label.push_back(row.exact_label);
  type.push_back(row.type);
  scene.push_back(row.scene);
  split.push_back(row.split);
}

void assign_splits(PairDataset& dataset, const SplitSettings& settings) {
  if (!(settings.training >= 0.0 && settings.selection >= 0.0 && settings.training + settings.selection <= 1.0))
    throw std::invalid_argument("split fractions must be non-negative and sum to at most 1");
  const std::size_t n = dataset.row_count();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  seeded_shuffle(order, settings.seed);
  const auto training = static_cast<std::size_t>(std::floor(settings.training * static_cast<double>(n)));
  const auto selection = static_cast<std::size_t>(std::floor(settings.selection * static_cast<double>(n)));
  for (std::size_t k = 0; k < n; ++k)
    dataset.split[order[k]] = k < training ? Split::Training : (k < training + selection ? Split::Selection : Split::Testing);
}

void write_pair_dataset_csv(const PairDataset& dataset, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open for writing");
  for (const std::string& name : dataset.feature_names) file << name << ',';
  file << "filter_label,exact_label,type,scene,split\n";
  char number[32];
  for (std::size_t i = 0; i < dataset.row_count(); ++i) {
    for (std::size_t f = 0; f < dataset.feature_count(); ++f) {
      std::snprintf(number, sizeof number, "%.17g", dataset.row(i)[f]);
      file << number << ',';
    }
    file << dataset.filter_label[i] << ',' << dataset.exact_label[i] << ',' << pair_kind_name(dataset.type[i]) << ','
         << dataset.scene[i] << ',' << split_name(dataset.split[i]) << '\n';
  }
  if (!file.flush()) throw std::runtime_error(path + ": write failed");
}

PairDataset read_pair_dataset_csv(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open the data set");
  std::string line;
  if (!std::getline(file, line)) throw std::runtime_error(path + ": empty file, expected a CSV header");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> header = split_fields(line);
  const std::size_t labels = std::size(kLabelColumns);
  if (header.size() <= labels ||
      !std::equal(std::begin(kLabelColumns), std::end(kLabelColumns), header.end() - static_cast<long>(labels)))
    fail(path, 1, "header must be feature columns then filter_label,exact_label,type,scene,split");
  PairDataset dataset;
  dataset.feature_names.assign(header.begin(), header.end() - static_cast<long>(labels));
  const std::size_t features = dataset.feature_count();
  std::size_t line_number = 1;
  while (std::getline(file, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size())
      fail(path, line_number, std::to_string(fields.size()) + " fields, the header has " + std::to_string(header.size()));
    for (std::size_t f = 0; f < features; ++f)
      dataset.features.push_back(parse_number(fields[f], path, line_number, header[f]));
    dataset.filter_label.push_back(parse_label(fields[features], path, line_number, "filter_label"));
    dataset.exact_label.push_back(parse_label(fields[features + 1], path, line_number, "exact_label"));
    const std::string& type = fields[features + 2];
    if (type != "VF" && type != "EE") fail(path, line_number, "type '" + type + "' is not VF or EE");
    dataset.type.push_back(type == "VF" ? PairKind::VertexFace : PairKind::EdgeEdge);
    dataset.scene.push_back(fields[features + 3]);
    const std::string& split = fields[features + 4];
    if (split == "training") dataset.split.push_back(Split::Training);
    else if (split == "selection") dataset.split.push_back(Split::Selection);
    else if (split == "testing") dataset.split.push_back(Split::Testing);
    else fail(path, line_number, "split '" + split + "' is not training, selection or testing");
  }
  if (dataset.row_count() == 0) throw std::runtime_error(path + ": the data set has no rows");
  return dataset;
}

std::vector<std::size_t> varying_feature_columns(const PairDataset& dataset) {
  std::vector<std::size_t> columns;
  for (std::size_t f = 0; f < dataset.feature_count(); ++f) {
    double lo = 0.0, hi = 0.0;
    for (std::size_t i = 0; i < dataset.row_count(); ++i) {
      const double value = dataset.row(i)[f];
      lo = i == 0 ? value : std::min(lo, value);
      hi = i == 0 ? value : std::max(hi, value);
    }
    if (hi > lo) columns.push_back(f);
  }
  return columns;
}

ClassBalance class_balance(const PairDataset& dataset) {
  ClassBalance balance;
  for (std::size_t i = 0; i < dataset.row_count(); ++i) {
    const auto s = static_cast<std::size_t>(dataset.split[i]);
    ++balance.rows[s];
    balance.filter_positive[s] += static_cast<std::size_t>(dataset.filter_label[i]);
    balance.exact_positive[s] += static_cast<std::size_t>(dataset.exact_label[i]);
  }
  return balance;
}

PairDataset rebalance_training_rows(const PairDataset& dataset, double ratio, unsigned long long seed) {
  if (!(ratio >= 1.0)) throw std::invalid_argument("re-balancing ratio must be at least 1");
  std::vector<std::size_t> by_class[2];
  for (std::size_t i = 0; i < dataset.row_count(); ++i)
    if (dataset.split[i] == Split::Training) by_class[dataset.filter_label[i]].push_back(i);
  const int minority = by_class[0].size() <= by_class[1].size() ? 0 : 1;
  std::vector<std::size_t>& majority = by_class[1 - minority];
  seeded_shuffle(majority, seed);
  // Compared in double first: a huge ratio (or infinity) would overflow the conversion to a count.
  const double wanted = std::ceil(ratio * static_cast<double>(by_class[minority].size()));
  const std::size_t keep =
      wanted >= static_cast<double>(majority.size()) ? majority.size() : static_cast<std::size_t>(wanted);
  std::vector<bool> kept(dataset.row_count(), true);
  for (std::size_t k = keep; k < majority.size(); ++k) kept[majority[k]] = false;
  PairDataset result;
  result.feature_names = dataset.feature_names;
  for (std::size_t i = 0; i < dataset.row_count(); ++i)
    if (kept[i]) append_row(result, dataset, i);
  return result;
}

}  // namespace clothcd::learning
