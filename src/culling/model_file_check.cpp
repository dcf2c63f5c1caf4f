// Nesting depth by a linear scan: comments, CDATA sections, declarations and processing instructions are skipped,
// closing tags go up a level, opening tags that do not close themselves go down one (quoted attribute values may hold
// '>'). Anything the scan cannot follow (an unterminated tag) is left to the parser's own error.
#include "culling/model_file_check.hpp"

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace clothcd::learning {
namespace {

// Position of the '>' ending the tag that starts at `begin`, skipping quoted values; npos when unterminated.
std::size_t tag_end(const std::string& text, std::size_t begin) {
  char quote = 0;
  for (std::size_t i = begin; i < text.size(); ++i) {
    const char c = text[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return i;
    }
  }
  return std::string::npos;
}

// The position just past `terminator` from `from` on; npos when it does not occur.
std::size_t past(const std::string& text, std::size_t from, const char* terminator) {
  const std::size_t at = text.find(terminator, from);
  return at == std::string::npos ? at : at + std::char_traits<char>::length(terminator);
}

}  // namespace

void check_model_file_shape(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return;
  const std::streamoff size = in.tellg();
  if (size > kMaxModelFileBytes) {
    throw std::runtime_error(path + ": " + std::to_string(size) + " bytes, larger than any model (at most " +
                             std::to_string(kMaxModelFileBytes) + ")");
  }
  in.seekg(0);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int depth = 0;
  std::size_t i = text.find('<');
  while (i != std::string::npos && i + 1 < text.size()) {
    std::size_t next;
    if (text.compare(i, 4, "<!--") == 0) {
      next = past(text, i + 4, "-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      next = past(text, i + 9, "]]>");
    } else if (text[i + 1] == '?') {
      next = past(text, i + 2, "?>");
    } else if (text[i + 1] == '!') {
      next = past(text, i + 2, ">");
    } else {
      const std::size_t end = tag_end(text, i + 1);
      if (end == std::string::npos) return;
      if (text[i + 1] == '/') {
        depth = depth > 0 ? depth - 1 : 0;
      } else if (text[end - 1] != '/' && ++depth > kMaxModelNesting) {
        throw std::runtime_error(path + ": elements nested more than " + std::to_string(kMaxModelNesting) +
                                 " levels deep: not a model file");
      }
      next = end + 1;
    }
    if (next == std::string::npos) return;
    i = text.find('<', next);
  }
}

}  // namespace clothcd::learning
