// Model card I/O: a small JSON file beside OpenNN's XML (features, dropped columns, data set, neurons, operating point,
// metrics).
#include "clothcd/learning/model_card.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "learning/json_lite.hpp"

namespace clothcd::learning {
namespace {

std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string string_list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + json::quote(items[i]);
  return out + "]";
}

const json::Value& member(const json::Value& root, const std::string& key, json::Value::Kind kind,
                          const std::string& path) {
  const json::Value* value = root.find(key);
  if (!value) throw std::runtime_error(path + ": model card lacks '" + key + "'");
  if (value->kind != kind) throw std::runtime_error(path + ": model card field '" + key + "' has the wrong type");
  return *value;
}

double number(const json::Value& root, const std::string& key, const std::string& path) {
  const double value = member(root, key, json::Value::Kind::Number, path).number;
  if (!std::isfinite(value)) throw std::runtime_error(path + ": model card field '" + key + "' is not finite");
  return value;
}

// A whole number in [0, below): larger values would not convert (2^64 + 15 became 0, 4294967297 a version of 1).
unsigned long long whole(const json::Value& root, const std::string& key, const std::string& path, double below) {
  const double value = number(root, key, path);
  if (value < 0.0 || value != std::floor(value) || !(value < below))
    throw std::runtime_error(path + ": model card field '" + key + "' is not a whole number from 0 below " +
                             number_text(below));
  return static_cast<unsigned long long>(value);
}

// A count (of rows, features, neurons, ...): a whole number below 2^53, where doubles stop counting exactly.
std::size_t count(const json::Value& root, const std::string& key, const std::string& path) {
  return static_cast<std::size_t>(whole(root, key, path, 0x1p53));
}

std::vector<std::string> strings(const json::Value& root, const std::string& key, const std::string& path) {
  std::vector<std::string> out;
  for (const json::Value& item : member(root, key, json::Value::Kind::Array, path).array) {
    if (item.kind != json::Value::Kind::String)
      throw std::runtime_error(path + ": model card field '" + key + "' must hold strings");
    out.push_back(item.string);
  }
  return out;
}

}  // namespace

void write_model_card(const ModelCard& card, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open for writing");
  file << "{\n"
       << "  \"format\": \"clothcd pair network\",\n"
       << "  \"feature_version\": " << card.feature_version << ",\n"
       << "  \"feature_count\": " << card.feature_count << ",\n"
       << "  \"features\": " << string_list(card.features) << ",\n"
       << "  \"inputs\": " << string_list(card.inputs) << ",\n"
       << "  \"dropped_columns\": " << string_list(card.dropped_columns) << ",\n"
       << "  \"dataset\": " << json::quote(card.dataset) << ",\n"
       << "  \"rows\": {\"training\": " << card.rows_training << ", \"selection\": " << card.rows_selection
       << ", \"testing\": " << card.rows_testing << "},\n"
       << "  \"hidden_neurons\": " << card.hidden_neurons << ",\n"
       << "  \"max_neurons\": " << card.max_neurons << ",\n"
       << "  \"trials\": " << card.trials << ",\n"
       << "  \"seed\": " << card.seed << ",\n"
       << "  \"decision_threshold\": " << number_text(card.decision_threshold) << ",\n"
       << "  \"drop_below\": " << number_text(card.drop_below) << ",\n"
       << "  \"keep_from\": " << number_text(card.keep_from) << ",\n"
       << "  \"metrics\": {";
  for (std::size_t i = 0; i < card.metrics.size(); ++i)
    file << (i ? ",\n    " : "\n    ") << json::quote(card.metrics[i].first) << ": " << number_text(card.metrics[i].second);
  file << "\n  }\n}\n";
  if (!file.flush()) throw std::runtime_error(path + ": write failed");
}

ModelCard read_model_card(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open the model card");
  std::stringstream text;
  text << file.rdbuf();
  const json::Value root = json::parse(text.str(), path);
  if (root.kind != json::Value::Kind::Object) throw std::runtime_error(path + ": model card is not a JSON object");
  ModelCard card;
  card.feature_version = static_cast<int>(whole(root, "feature_version", path, 1e6));
  card.feature_count = count(root, "feature_count", path);
  card.features = strings(root, "features", path);
  card.inputs = strings(root, "inputs", path);
  if (card.feature_count != card.features.size())
    throw std::runtime_error(path + ": feature_count is " + std::to_string(card.feature_count) + " but " +
                             std::to_string(card.features.size()) + " features are listed");
  card.dropped_columns = strings(root, "dropped_columns", path);
  card.dataset = member(root, "dataset", json::Value::Kind::String, path).string;
  const json::Value& rows = member(root, "rows", json::Value::Kind::Object, path);
  card.rows_training = count(rows, "training", path);
  card.rows_selection = count(rows, "selection", path);
  card.rows_testing = count(rows, "testing", path);
  card.hidden_neurons = count(root, "hidden_neurons", path);
  card.max_neurons = count(root, "max_neurons", path);
  card.trials = count(root, "trials", path);
  card.seed = whole(root, "seed", path, 0x1p64);
  card.decision_threshold = number(root, "decision_threshold", path);
  card.drop_below = number(root, "drop_below", path);
  card.keep_from = root.find("keep_from") ? number(root, "keep_from", path) : card.decision_threshold;
  for (const auto& [name, value] : member(root, "metrics", json::Value::Kind::Object, path).object)
    if (value.kind == json::Value::Kind::Number) card.metrics.emplace_back(name, value.number);
  return card;
}

}  // namespace clothcd::learning
