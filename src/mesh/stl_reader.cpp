// The STL reader (see mesh_readers.hpp). A file is binary when its size is exactly what its triangle count asks for
// (84 + 50 n bytes), ASCII when it starts with "solid" otherwise; binary files may start with "solid" too.
#include <cmath>
#include <cstdint>

#include "mesh/file_cursor.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd::detail {
namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kTriangleBytes = 50;  // normal, three corners (float x, y, z each), attribute byte count

bool starts_with_solid(std::string_view bytes) {
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && bytes.substr(first, 5) == "solid";
}

TriangleMesh read_binary(std::string_view bytes, std::size_t triangles, const std::string& file) {
  ByteCursor in(bytes, kHeaderBytes + 4, false, file);
  MeshBuilder mesh;
  mesh.positions.reserve(triangles * 9);
  mesh.triangles.reserve(triangles * 3);
  for (std::size_t t = 0; t < triangles; ++t) {
    in.skip(12);  // the normal
    for (int corner = 0; corner < 3; ++corner) {
      for (int axis = 0; axis < 3; ++axis) {
        const std::size_t offset = in.position();
        const float value = float_from_bits(static_cast<std::uint32_t>(in.read_bits<4>()));
        if (!std::isfinite(value)) fail_at_byte(file, offset, "triangle " + std::to_string(t) + ": non-finite coordinate");
        mesh.positions.push_back(value);
      }
    }
    in.skip(2);  // the attribute byte count
    const int first = static_cast<int>(3 * t);
    const int corners[3] = {first, first + 1, first + 2};
    mesh.add_polygon(corners, 3);
  }
  return mesh.finish();
}

TriangleMesh read_ascii(std::string_view text, const std::string& file) {
  enum class Place { outside, solid, facet, loop } place = Place::outside;
  MeshBuilder mesh;
  std::vector<int> corners;
  LineCursor lines(text);
  std::string_view line;
  while (lines.next(line)) {
    Tokens words(line);
    std::string_view keyword, token;
    if (!words.next(keyword)) continue;
    const std::size_t at = lines.line_number();
    if (keyword == "solid" && place == Place::outside) {
      place = Place::solid;
      continue;  // the rest of the line is the solid's name
    }
    if (keyword == "endsolid" && place == Place::solid) {
      place = Place::outside;
      continue;
    }
    if (keyword == "facet" && place == Place::solid) {
      place = Place::facet;
    } else if (keyword == "outer" && place == Place::facet && words.next(token) && token == "loop") {
      place = Place::loop;
      corners.clear();
    } else if (keyword == "vertex" && place == Place::loop) {
      for (int axis = 0; axis < 3; ++axis) {
        double value = 0.0;
        if (!words.next(token) || !parse_double(token, value))
          fail_at_line(file, at, "a vertex line needs three numbers");
        if (!std::isfinite(value)) fail_at_line(file, at, "non-finite vertex coordinate '" + std::string(token) + "'");
        mesh.positions.push_back(value);
      }
      if (!words.empty()) fail_at_line(file, at, "unexpected text after the vertex");
      corners.push_back(static_cast<int>(mesh.positions.size() / 3 - 1));
    } else if (keyword == "endloop" && place == Place::loop) {
      if (corners.size() < 3)
        fail_at_line(file, at, "a facet needs 3 or more vertices, this one has " + std::to_string(corners.size()));
      mesh.add_polygon(corners.data(), corners.size());
      place = Place::facet;
    } else if (keyword == "endfacet" && place == Place::facet) {
      place = Place::solid;
    } else {
      fail_at_line(file, at, "unexpected '" + std::string(keyword.substr(0, 40)) + "' in an ASCII STL file");
    }
  }
  if (place != Place::outside) throw MeshError(file, "the ASCII STL file ends inside a solid (truncated file)");
  return mesh.finish();
}

}  // namespace

TriangleMesh read_stl(std::string_view bytes, const std::string& file) {
  if (bytes.size() >= kHeaderBytes + 4) {
    ByteCursor count(bytes, kHeaderBytes, false, file);
    const std::uint64_t triangles = count.read_bits<4>();
    const std::uint64_t size = kHeaderBytes + 4 + kTriangleBytes * triangles;
    if (size == bytes.size()) return read_binary(bytes, static_cast<std::size_t>(triangles), file);
    if (!starts_with_solid(bytes))
      fail_at_byte(file, kHeaderBytes,
                   "binary STL declares " + std::to_string(triangles) + " triangles, which take " + std::to_string(size) +
                       " bytes, but the file has " + std::to_string(bytes.size()) +
                       " (truncated file, trailing bytes or a wrong count)");
  } else if (!starts_with_solid(bytes)) {
    throw MeshError(file, "not an STL file (shorter than a binary STL header and not starting with 'solid')");
  }
  return read_ascii(bytes, file);
}

}  // namespace clothcd::detail
