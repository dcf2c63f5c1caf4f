// A JSON report written item by item (json_stream.hpp).
#include "json_stream.hpp"

#include <fstream>
#include <iostream>
#include <stdexcept>

namespace clothcd::cli {
namespace {

// `text` with `indent` after each line break.
std::string indented(const std::string& text, const std::string& indent) {
  std::string result;
  result.reserve(text.size());
  for (const char ch : text) {
    result += ch;
    if (ch == '\n') result += indent;
  }
  return result;
}

}  // namespace

JsonStream::JsonStream(std::ostream& out, const Json& head) : out_(out) {
  const std::string text = head.dump(2);
  out_.write(text.data(), static_cast<std::streamsize>(text.size() - 2));  // without the closing "\n}"
}

void JsonStream::array(const std::string& name,
                       const std::function<void(const std::function<void(const Json&)>&)>& items) {
  out_ << ",\n  " << Json(name).dump() << ": [";
  bool first = true;
  items([&](const Json& item) {
    out_ << (first ? "\n    " : ",\n    ") << indented(item.dump(2), "    ");
    first = false;
  });
  out_ << (first ? "]" : "\n  ]");
}

void JsonStream::field(const std::string& name, const Json& value) {
  out_ << ",\n  " << Json(name).dump() << ": " << indented(value.dump(2), "  ");
}

void JsonStream::close() { out_ << "\n}\n"; }

void write_to(bool to_stdout, const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (to_stdout) write(std::cout);
  if (path.empty()) return;
  std::ofstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open for writing");
  write(file);
  file.close();  // flushes: a full disk shows here
  if (!file) throw std::runtime_error(path + ": write failed");
}

}  // namespace clothcd::cli
