// Model card I/O: a small JSON file beside OpenNN's XML (features, dropped columns, data set, neurons, operating point,
// metrics).
#include "clothcd/culling/model_card.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace clothcd::learning {
namespace {

using Json = nlohmann::ordered_json;  // keeps the metrics in the order of the file

std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string quote(const std::string& text) { return Json(text).dump(); }

std::string string_list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + quote(items[i]);
  return out + "]";
}

// `text` parsed; a malformed document or a key given twice in one object is an error naming `path`.
Json parse_card(const std::string& text, const std::string& path) {
  std::vector<std::set<std::string>> keys;  // the keys seen so far in each open object
  std::string duplicate;
  const Json::parser_callback_t check_keys = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) keys.emplace_back();
    if (event == Json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == Json::parse_event_t::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second &&
        duplicate.empty())
      duplicate = parsed.get<std::string>();
    return true;
  };
  Json root;
  try {
    root = Json::parse(text, check_keys);
  } catch (const Json::parse_error& error) {
    std::string problem = error.what();
    const std::size_t colon = problem.find(": ", problem.find("parse error"));
    if (colon != std::string::npos) problem = problem.substr(colon + 2);
    throw std::runtime_error(path + ": malformed JSON: " + problem + " at offset " + std::to_string(error.byte));
  } catch (const Json::exception& error) {  // e.g. a number beyond the doubles (1e400)
    throw std::runtime_error(path + ": malformed JSON: " + error.what());
  }
  if (!duplicate.empty()) throw std::runtime_error(path + ": malformed JSON: duplicate key '" + duplicate + "'");
  return root;
}

enum class Kind { Number, String, Array, Object };

bool has_kind(const Json& value, Kind kind) {
  switch (kind) {
    case Kind::Number:
      return value.is_number();
    case Kind::String:
      return value.is_string();
    case Kind::Array:
      return value.is_array();
    case Kind::Object:
      return value.is_object();
  }
  return false;
}

const Json& member(const Json& root, const std::string& key, Kind kind, const std::string& path) {
  const auto value = root.find(key);
  if (value == root.end()) throw std::runtime_error(path + ": model card lacks '" + key + "'");
  if (!has_kind(*value, kind)) throw std::runtime_error(path + ": model card field '" + key + "' has the wrong type");
  return *value;
}

double number(const Json& root, const std::string& key, const std::string& path) {
  const double value = member(root, key, Kind::Number, path).get<double>();
  if (!std::isfinite(value)) throw std::runtime_error(path + ": model card field '" + key + "' is not finite");
  return value;
}

// A whole number in [0, below): larger values would not convert (2^64 + 15 became 0, 4294967297 a version of 1).
unsigned long long whole(const Json& root, const std::string& key, const std::string& path, double below) {
  const double value = number(root, key, path);
  if (value < 0.0 || value != std::floor(value) || !(value < below))
    throw std::runtime_error(path + ": model card field '" + key + "' is not a whole number from 0 below " +
                             number_text(below));
  return static_cast<unsigned long long>(value);
}

// A count (of rows, features, neurons, ...): a whole number below 2^53, where doubles stop counting exactly.
std::size_t count(const Json& root, const std::string& key, const std::string& path) {
  return static_cast<std::size_t>(whole(root, key, path, 0x1p53));
}

std::vector<std::string> strings(const Json& root, const std::string& key, const std::string& path) {
  std::vector<std::string> out;
  for (const Json& item : member(root, key, Kind::Array, path)) {
    if (!item.is_string()) throw std::runtime_error(path + ": model card field '" + key + "' must hold strings");
    out.push_back(item.get<std::string>());
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
       << "  \"dataset\": " << quote(card.dataset) << ",\n"
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
    file << (i ? ",\n    " : "\n    ") << quote(card.metrics[i].first) << ": " << number_text(card.metrics[i].second);
  file << "\n  }\n}\n";
  if (!file.flush()) throw std::runtime_error(path + ": write failed");
}

ModelCard read_model_card(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open the model card");
  std::stringstream text;
  text << file.rdbuf();
  const Json root = parse_card(text.str(), path);
  if (!root.is_object()) throw std::runtime_error(path + ": model card is not a JSON object");
  ModelCard card;
  card.feature_version = static_cast<int>(whole(root, "feature_version", path, 1e6));
  card.feature_count = count(root, "feature_count", path);
  card.features = strings(root, "features", path);
  card.inputs = strings(root, "inputs", path);
  if (card.feature_count != card.features.size())
    throw std::runtime_error(path + ": feature_count is " + std::to_string(card.feature_count) + " but " +
                             std::to_string(card.features.size()) + " features are listed");
  card.dropped_columns = strings(root, "dropped_columns", path);
  card.dataset = member(root, "dataset", Kind::String, path).get<std::string>();
  const Json& rows = member(root, "rows", Kind::Object, path);
  card.rows_training = count(rows, "training", path);
  card.rows_selection = count(rows, "selection", path);
  card.rows_testing = count(rows, "testing", path);
  card.hidden_neurons = count(root, "hidden_neurons", path);
  card.max_neurons = count(root, "max_neurons", path);
  card.trials = count(root, "trials", path);
  card.seed = whole(root, "seed", path, 0x1p64);
  card.decision_threshold = number(root, "decision_threshold", path);
  card.drop_below = number(root, "drop_below", path);
  card.keep_from = root.contains("keep_from") ? number(root, "keep_from", path) : card.decision_threshold;
  for (const auto& [name, value] : member(root, "metrics", Kind::Object, path).items())
    if (value.is_number()) card.metrics.emplace_back(name, value.get<double>());
  return card;
}

}  // namespace clothcd::learning
