// The Wavefront OBJ reader (see mesh_readers.hpp).
#include <climits>
#include <cmath>
#include <utility>

#include "mesh/file_cursor.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd::detail {
namespace {

// Reads the position of a `v` line: three numbers, then optionally a weight or a colour (numbers too).
void read_vertex(Tokens& tokens, MeshBuilder& mesh, const std::string& file, std::size_t line) {
  std::string_view token;
  int count = 0;
  while (tokens.next(token)) {
    double value = 0.0;
    if (!parse_double(token, value)) fail_at_line(file, line, "vertex coordinate '" + std::string(token) + "' is not a number");
    if (count < 3) {
      if (!std::isfinite(value)) fail_at_line(file, line, "non-finite vertex coordinate '" + std::string(token) + "'");
      mesh.positions.push_back(value);
    }
    ++count;
  }
  if (count < 3) fail_at_line(file, line, "a vertex needs three coordinates, the line has " + std::to_string(count));
}

}  // namespace

TriangleMesh read_obj(std::string_view text, const std::string& file) {
  MeshBuilder mesh;
  std::vector<int> corners;
  // Corners naming a vertex defined further down the file: checked once every vertex is known.
  std::vector<std::pair<std::size_t, long long>> forward;
  LineCursor lines(text);
  std::string_view line;
  while (lines.next(line)) {
    Tokens tokens(line, true);
    std::string_view keyword;
    if (!tokens.next(keyword)) continue;
    if (keyword == "v") {
      read_vertex(tokens, mesh, file, lines.line_number());
      continue;
    }
    if (keyword != "f") continue;  // vt, vn, o, g, s, usemtl, mtllib, l, p, ...: not part of the surface
    const long long defined = static_cast<long long>(mesh.positions.size() / 3);
    corners.clear();
    for (std::string_view token; tokens.next(token);) {
      long long number = 0;
      if (!parse_integer(token.substr(0, token.find('/')), number))
        fail_at_line(file, lines.line_number(), "face corner '" + std::string(token) + "' has no vertex number");
      const long long index = number < 0 ? defined + number : number - 1;
      if (number == 0 || index < 0 || index >= INT_MAX)
        fail_at_line(file, lines.line_number(),
                     "face vertex number " + std::to_string(number) + " is out of range (" + std::to_string(defined) +
                         " vertices so far; numbers start at 1, negative ones count back from the last)");
      if (index >= defined) forward.emplace_back(lines.line_number(), index);
      corners.push_back(static_cast<int>(index));
    }
    if (corners.size() < 3)
      fail_at_line(file, lines.line_number(), "a face needs 3 or more corners, this one has " + std::to_string(corners.size()));
    mesh.add_polygon(corners.data(), corners.size());
  }
  const long long vertices = static_cast<long long>(mesh.positions.size() / 3);
  for (const auto& [line_number, index] : forward) {
    if (index >= vertices)
      fail_at_line(file, line_number, "face vertex number " + std::to_string(index + 1) + " is out of range 1.." +
                                          std::to_string(vertices));
  }
  return mesh.finish();
}

}  // namespace clothcd::detail
