// Number parsing and error helpers of the mesh readers (see file_cursor.hpp).
#include "mesh/file_cursor.hpp"

#include <charconv>
#include <cstdlib>
#include <system_error>

namespace clothcd::detail {
namespace {

// Removes a leading '+' (from_chars takes only '-'); false when a second sign follows it.
bool drop_plus(std::string_view& token) {
  if (token.empty() || token.front() != '+') return true;
  token.remove_prefix(1);
  return !token.empty() && token.front() != '+' && token.front() != '-';
}

}  // namespace

bool parse_double(std::string_view token, double& value) {
  if (!drop_plus(token)) return false;
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  if (stop != end) return false;
  if (error == std::errc::result_out_of_range) {
    // Below the smallest subnormal or above the largest double: strtod rounds to zero or infinity as IEEE does.
    const std::string copy(token);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return error == std::errc();
}

bool parse_integer(std::string_view token, long long& value) {
  if (!drop_plus(token)) return false;
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  return error == std::errc() && stop == end;
}

void fail_at_line(const std::string& file, std::size_t line, const std::string& problem) {
  throw MeshError(file, "line " + std::to_string(line) + ": " + problem);
}

void fail_at_byte(const std::string& file, std::size_t offset, const std::string& problem) {
  throw MeshError(file, "byte offset " + std::to_string(offset) + ": " + problem);
}

}  // namespace clothcd::detail
