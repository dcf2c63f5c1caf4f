// Recursive-descent JSON reader (RFC 8259 subset: no \u escapes) for the model cards clothcd itself writes.
#include "learning/json_lite.hpp"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

namespace clothcd::learning::json {
namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& context) : text_(text), context_(context) {}

  Value document() {
    Value value = parse_value(0);
    skip_space();
    if (pos_ != text_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw std::runtime_error(context_ + ": malformed JSON: " + problem + " at offset " + std::to_string(pos_));
  }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool consume(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!consume(c)) fail(std::string("expected '") + c + "'");
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }
  std::string parse_string() {
    expect('"');
    std::string out;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      char c = text_[pos_++];
      if (c == '\\') {
        if (pos_ >= text_.size()) fail("unterminated escape");
        const char e = text_[pos_++];
        c = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
        if (e != 'n' && e != 't' && e != 'r' && e != '"' && e != '\\' && e != '/') fail("unsupported escape");
      }
      out += c;
    }
    if (pos_ >= text_.size()) fail("unterminated string");
    ++pos_;
    return out;
  }
  Value parse_value(int depth) {
    if (depth > 64) fail("nesting too deep");
    skip_space();
    if (pos_ >= text_.size()) fail("unexpected end");
    Value value;
    const char c = text_[pos_];
    if (c == '{') {
      ++pos_;
      value.kind = Value::Kind::Object;
      if (consume('}')) return value;
      do {
        skip_space();
        std::string key = parse_string();
        if (value.find(key)) fail("duplicate key '" + key + "'");
        expect(':');
        value.object.emplace_back(std::move(key), parse_value(depth + 1));
      } while (consume(','));
      expect('}');
    } else if (c == '[') {
      ++pos_;
      value.kind = Value::Kind::Array;
      if (consume(']')) return value;
      do value.array.push_back(parse_value(depth + 1));
      while (consume(','));
      expect(']');
    } else if (c == '"') {
      value.kind = Value::Kind::String;
      value.string = parse_string();
    } else if (literal("true") || literal("false")) {
      value.kind = Value::Kind::Bool;
      value.boolean = text_[pos_ - 1] == 'e' && text_[pos_ - 2] == 'u';
    } else if (literal("null")) {
      value.kind = Value::Kind::Null;
    } else {
      const char* begin = text_.c_str() + pos_;
      char* end = nullptr;
      value.number = std::strtod(begin, &end);
      if (end == begin) fail("unexpected character");
      value.kind = Value::Kind::Number;
      pos_ += static_cast<std::size_t>(end - begin);
    }
    return value;
  }

  const std::string& text_;
  const std::string& context_;
  std::size_t pos_ = 0;
};

}  // namespace

const Value* Value::find(const std::string& key) const {
  for (const auto& [name, value] : object)
    if (name == key) return &value;
  return nullptr;
}

Value parse(const std::string& text, const std::string& context) { return Parser(text, context).document(); }

std::string quote(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace clothcd::learning::json
