#pragma once
// The mesh readers' shared pieces: a cursor over the lines of a text, a splitter of a line into whitespace-separated
// tokens, exact number parsing, and a cursor over the bytes of a binary body. Every error names the file and the
// line (text) or byte offset (binary). Internal.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "clothcd/mesh/mesh_error.hpp"

namespace clothcd::detail {

/// The lines of a text, one at a time, numbered from 1; "\n" and "\r\n" both end a line.
class LineCursor {
 public:
  /// Reads `text` from byte `start`; `first_line` is the number of the line starting there.
  explicit LineCursor(std::string_view text, std::size_t start = 0, std::size_t first_line = 1)
      : text_(text), position_(start), next_line_number_(first_line) {}

  /// Stores the next line (without its line end) in `line` and returns true; false at the end of the text.
  bool next(std::string_view& line) {
    if (position_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', position_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(position_, stop - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = end == std::string_view::npos ? text_.size() : end + 1;
    line_number_ = next_line_number_++;
    return true;
  }
  /// Number of the line `next` returned last (0 before the first).
  [[nodiscard]] std::size_t line_number() const { return line_number_; }
  /// Byte offset of the first byte after the line `next` returned last.
  [[nodiscard]] std::size_t position() const { return position_; }
  /// Bytes after the line `next` returned last.
  [[nodiscard]] std::size_t remaining() const { return text_.size() - position_; }

 private:
  std::string_view text_;
  std::size_t position_;
  std::size_t next_line_number_;
  std::size_t line_number_ = 0;
};

/// True for the characters that separate tokens: space, tab, carriage return, vertical tab, form feed.
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// The whitespace-separated tokens of one line, left to right.
class Tokens {
 public:
  /// Splits `line`; a '#' starts a comment to the end of the line when `hash_comments` is set.
  explicit Tokens(std::string_view line, bool hash_comments = false) : line_(line) {
    if (hash_comments) line_ = line_.substr(0, line_.find('#'));
  }
  /// Stores the next token in `token` and returns true; false when the line has no more.
  bool next(std::string_view& token) {
    while (position_ < line_.size() && is_blank(line_[position_])) ++position_;
    if (position_ >= line_.size()) return false;
    const std::size_t begin = position_;
    while (position_ < line_.size() && !is_blank(line_[position_])) ++position_;
    token = line_.substr(begin, position_ - begin);
    return true;
  }
  /// True when no token is left.
  [[nodiscard]] bool empty() {
    while (position_ < line_.size() && is_blank(line_[position_])) ++position_;
    return position_ >= line_.size();
  }

 private:
  std::string_view line_;
  std::size_t position_ = 0;
};

/// Parses a whole token as a double, correctly rounded (the file's decimal gives the nearest double, so a double
/// written with 17 significant digits comes back bit for bit); a leading '+' is allowed, a value below the smallest
/// subnormal reads as zero, one beyond the largest double as infinity. False when the token is not a number.
bool parse_double(std::string_view token, double& value);

/// Parses a whole token as a decimal integer (optional sign); false when it is not one or lies outside 64 bits.
bool parse_integer(std::string_view token, long long& value);

/// Throws MeshError "<file>: line <line>: <problem>".
[[noreturn]] void fail_at_line(const std::string& file, std::size_t line, const std::string& problem);

/// Throws MeshError "<file>: byte offset <offset>: <problem>".
[[noreturn]] void fail_at_byte(const std::string& file, std::size_t offset, const std::string& problem);

/// The bytes of a binary body, read in order as little- or big-endian scalars.
class ByteCursor {
 public:
  /// Reads `bytes` from offset `start`; `file` names the file in errors.
  ByteCursor(std::string_view bytes, std::size_t start, bool big_endian, const std::string& file)
      : bytes_(bytes), position_(start), big_endian_(big_endian), file_(file) {}

  /// Offset of the next byte.
  [[nodiscard]] std::size_t position() const { return position_; }
  /// Bytes left.
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - position_; }

  /// Throws a truncation error naming `what` unless `count` more bytes are left.
  void require(std::size_t count, std::string_view what) const {
    if (count > remaining())
      fail_at_byte(file_, position_, "the file ends inside " + std::string(what) + " (truncated file or wrong count)");
  }
  /// Skips `count` bytes (after require).
  void skip(std::size_t count) { position_ += count; }

  /// The next `Size` bytes as an unsigned integer in the file's byte order (after require).
  template <int Size>
  std::uint64_t read_bits() {
    std::uint64_t bits = 0;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes_.data() + position_);
    for (int i = 0; i < Size; ++i) {
      const int shift = 8 * (big_endian_ ? Size - 1 - i : i);
      bits |= static_cast<std::uint64_t>(data[i]) << shift;
    }
    position_ += Size;
    return bits;
  }

 private:
  std::string_view bytes_;
  std::size_t position_;
  bool big_endian_;
  const std::string& file_;
};

/// The float whose IEEE bits are `bits`.
inline float float_from_bits(std::uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// The double whose IEEE bits are `bits`.
inline double double_from_bits(std::uint64_t bits) {
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace clothcd::detail
