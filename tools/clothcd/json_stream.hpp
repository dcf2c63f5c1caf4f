#pragma once
// A JSON report written as it is serialised: a head object, then array fields one item at a time, never held whole
// in memory; the bytes are those Json::dump(2) gives for the whole report.

#include <cmath>
#include <functional>
#include <ostream>
#include <string>

#include "shared_options.hpp"

namespace clothcd::cli {

/// A time in milliseconds to the microsecond, for a report (the full 17 digits of the other numbers say nothing here).
inline double milliseconds(double ms) { return std::round(ms * 1000.0) / 1000.0; }

/// Writes a report in pieces: the head's fields, then arrays item by item, then the closing brace.
class JsonStream {
 public:
  /// Writes `head`'s fields (without its closing brace) to `out`.
  JsonStream(std::ostream& out, const Json& head);

  /// Appends the array field `name`, calling `items` with a function that writes one item.
  void array(const std::string& name, const std::function<void(const std::function<void(const Json&)>&)>& items);

  /// Appends the object field `name`.
  void field(const std::string& name, const Json& value);

  /// Writes the closing brace and a line break.
  void close();

 private:
  std::ostream& out_;
};

/// Calls `write` on stdout (with `to_stdout`) and on the file `path` (when not empty), which is then closed and
/// checked; throws std::runtime_error when it cannot be written.
void write_to(bool to_stdout, const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace clothcd::cli
