#pragma once
// A small JSON reader for model cards (objects, arrays, strings with simple escapes, numbers, true/false/null) and a
// string escaper for writing them. Private to the learning area.

#include <string>
#include <utility>
#include <vector>

namespace clothcd::learning::json {

/// One JSON value.
struct Value {
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> array;
  std::vector<std::pair<std::string, Value>> object;

  /// The member `key` of an object, or nullptr.
  [[nodiscard]] const Value* find(const std::string& key) const;
};

/// Parses `text`; throws std::runtime_error "<context>: <problem> at offset N" on malformed JSON.
[[nodiscard]] Value parse(const std::string& text, const std::string& context);

/// `text` as a quoted JSON string.
[[nodiscard]] std::string quote(const std::string& text);

}  // namespace clothcd::learning::json
