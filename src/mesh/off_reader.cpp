// The OFF reader (see mesh_readers.hpp).
#include <cmath>

#include "mesh/file_cursor.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd::detail {
namespace {

// The shortest text a vertex line ("0 0 0\n") and a face line ("0\n", refused later) can take.
constexpr long long kShortestVertexLine = 6;
constexpr long long kShortestFaceLine = 2;

// The next line holding something besides a # comment; false at the end of the text.
bool next_content_line(LineCursor& lines, std::string_view& line) {
  while (lines.next(line)) {
    if (!Tokens(line, true).empty()) return true;
  }
  return false;
}

// True for OFF headers whose vertex lines start with x y z: OFF with the optional ST (texture), C (colour) and
// N (normal) prefixes, in that order.
bool is_off_keyword(std::string_view word) {
  if (word.substr(0, 2) == "ST") word.remove_prefix(2);
  if (word.substr(0, 1) == "C") word.remove_prefix(1);
  if (word.substr(0, 1) == "N") word.remove_prefix(1);
  return word == "OFF";
}

long long read_count(Tokens& tokens, const char* what, const std::string& file, std::size_t line) {
  std::string_view token;
  long long count = 0;
  if (!tokens.next(token) || !parse_integer(token, count) || count < 0)
    fail_at_line(file, line, std::string("the ") + what + " count is missing or not a whole number >= 0");
  return count;
}

}  // namespace

TriangleMesh read_off(std::string_view text, const std::string& file) {
  LineCursor lines(text);
  std::string_view line;
  if (!next_content_line(lines, line)) throw MeshError(file, "the file holds no OFF header");
  Tokens header(line, true);
  std::string_view keyword;
  header.next(keyword);
  if (!is_off_keyword(keyword))
    fail_at_line(file, lines.line_number(), "not an OFF file, or an OFF variant that is not read (header '" +
                                                std::string(keyword) + "')");
  // The counts may follow the keyword on its line.
  Tokens counts = header;
  if (counts.empty()) {
    if (!next_content_line(lines, line)) throw MeshError(file, "the OFF file ends before its counts (truncated file)");
    counts = Tokens(line, true);
  }
  const std::size_t counts_line = lines.line_number();
  const long long vertex_count = read_count(counts, "vertex", file, counts_line);
  const long long face_count = read_count(counts, "face", file, counts_line);
  std::string_view token;
  long long edge_count = 0;
  if (counts.next(token) && !parse_integer(token, edge_count))
    fail_at_line(file, counts_line, "the edge count '" + std::string(token) + "' is not a whole number");
  if (!counts.empty()) fail_at_line(file, counts_line, "unexpected text after the counts");
  const long long room = static_cast<long long>(lines.remaining()) + 1;
  if (vertex_count > room / kShortestVertexLine || face_count > room / kShortestFaceLine ||
      vertex_count * kShortestVertexLine + face_count * kShortestFaceLine > room)
    fail_at_line(file, counts_line,
                 "the counts (" + std::to_string(vertex_count) + " vertices, " + std::to_string(face_count) +
                     " faces) need more than the " + std::to_string(room - 1) +
                     " bytes left in the file (truncated file or wrong count)");

  MeshBuilder mesh;
  mesh.positions.reserve(static_cast<std::size_t>(vertex_count) * 3);
  mesh.triangles.reserve(static_cast<std::size_t>(face_count) * 3);
  for (long long v = 0; v < vertex_count; ++v) {
    if (!next_content_line(lines, line))
      throw MeshError(file, "the file ends at vertex " + std::to_string(v) + " of " + std::to_string(vertex_count) +
                                " declared (truncated file or wrong count)");
    Tokens values(line, true);
    for (int axis = 0; axis < 3; ++axis) {
      double value = 0.0;
      if (!values.next(token)) fail_at_line(file, lines.line_number(), "a vertex line needs three coordinates");
      if (!parse_double(token, value))
        fail_at_line(file, lines.line_number(), "vertex coordinate '" + std::string(token) + "' is not a number");
      if (!std::isfinite(value))
        fail_at_line(file, lines.line_number(), "non-finite vertex coordinate '" + std::string(token) + "'");
      mesh.positions.push_back(value);
    }
  }
  std::vector<int> corners;
  for (long long f = 0; f < face_count; ++f) {
    if (!next_content_line(lines, line))
      throw MeshError(file, "the file ends at face " + std::to_string(f) + " of " + std::to_string(face_count) +
                                " declared (truncated file or wrong count)");
    Tokens values(line, true);
    long long size = 0;
    values.next(token);
    if (!parse_integer(token, size) || size < 3)
      fail_at_line(file, lines.line_number(), "face " + std::to_string(f) + " has '" + std::string(token) +
                                                  "' corners, a face needs 3 or more");
    corners.clear();
    for (long long k = 0; k < size; ++k) {
      long long index = 0;
      if (!values.next(token))
        fail_at_line(file, lines.line_number(), "face " + std::to_string(f) + " lists fewer than its " +
                                                    std::to_string(size) + " vertex indices");
      if (!parse_integer(token, index) || index < 0 || index >= vertex_count)
        fail_at_line(file, lines.line_number(), "face " + std::to_string(f) + " has vertex index '" +
                                                    std::string(token) + "', out of range 0.." +
                                                    std::to_string(vertex_count - 1));
      corners.push_back(static_cast<int>(index));
    }
    mesh.add_polygon(corners.data(), corners.size());  // a colour may follow the indices
  }
  if (next_content_line(lines, line)) fail_at_line(file, lines.line_number(), "text after the last face");
  return mesh.finish();
}

}  // namespace clothcd::detail
