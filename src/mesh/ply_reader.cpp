// The PLY reader (see mesh_readers.hpp): the header is read first, every count is checked against the bytes left in the
// file, then the body is read row by row, ASCII (one line per row) or binary (either byte order).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include "mesh/file_cursor.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd::detail {
namespace {

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool scalar_from_name(std::string_view name, Scalar& type) {
  static constexpr std::pair<std::string_view, Scalar> kNames[] = {
      {"char", Scalar::int8},     {"int8", Scalar::int8},       {"uchar", Scalar::uint8},    {"uint8", Scalar::uint8},
      {"short", Scalar::int16},   {"int16", Scalar::int16},     {"ushort", Scalar::uint16},  {"uint16", Scalar::uint16},
      {"int", Scalar::int32},     {"int32", Scalar::int32},     {"uint", Scalar::uint32},    {"uint32", Scalar::uint32},
      {"float", Scalar::float32}, {"float32", Scalar::float32}, {"double", Scalar::float64}, {"float64", Scalar::float64}};
  for (const auto& [text, value] : kNames) {
    if (text == name) {
      type = value;
      return true;
    }
  }
  return false;
}

std::size_t scalar_bytes(Scalar type) {
  switch (type) {
    case Scalar::int8: case Scalar::uint8: return 1;
    case Scalar::int16: case Scalar::uint16: return 2;
    case Scalar::int32: case Scalar::uint32: case Scalar::float32: return 4;
    case Scalar::float64: return 8;
  }
  return 8;
}

bool is_integer(Scalar type) { return type != Scalar::float32 && type != Scalar::float64; }

struct Property {
  std::string name;
  bool list = false;
  Scalar count_type = Scalar::uint8;  // lists only
  Scalar type = Scalar::float32;      // the value, or a list's items
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
  std::size_t line = 0;  // where it is declared
};

enum class Encoding { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_start = 0;  // byte offset of the first byte after end_header's line
  std::size_t body_line = 0;   // number of the first line after end_header
};

Property read_property(const std::vector<std::string_view>& words, const std::string& file, std::size_t line) {
  Property property;
  property.list = words.size() == 5;
  if (property.list && (!scalar_from_name(words[2], property.count_type) || !is_integer(property.count_type)))
    fail_at_line(file, line, "list count type '" + std::string(words[2]) + "' is not an integer type");
  const std::string_view type = words[words.size() - 2];
  if (!scalar_from_name(type, property.type)) fail_at_line(file, line, "PLY property type '" + std::string(type) + "' is unknown");
  property.name = words.back();
  return property;
}

Header read_header(std::string_view bytes, const std::string& file) {
  LineCursor lines(bytes);
  std::string_view line;
  if (!lines.next(line) || line != "ply") throw MeshError(file, "not a PLY file (the first line is not 'ply')");
  Header header;
  bool has_format = false;
  std::vector<std::string_view> words;
  while (lines.next(line)) {
    const std::size_t number = lines.line_number();
    Tokens tokens(line);
    words.clear();
    for (std::string_view word; words.size() < 6 && tokens.next(word);) words.push_back(word);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string_view keyword = words[0];
    if (keyword == "end_header" && words.size() == 1) {
      if (!has_format) fail_at_line(file, number, "the PLY header has no format line");
      header.body_start = lines.position();
      header.body_line = number + 1;
      return header;
    }
    if (keyword == "format" && words.size() == 3 && !has_format) {
      if (words[1] == "ascii") header.encoding = Encoding::ascii;
      else if (words[1] == "binary_little_endian") header.encoding = Encoding::binary_little_endian;
      else if (words[1] == "binary_big_endian") header.encoding = Encoding::binary_big_endian;
      else fail_at_line(file, number, "unknown PLY format '" + std::string(words[1]) + "'");
      if (words[2] != "1.0") fail_at_line(file, number, "unknown PLY version '" + std::string(words[2]) + "'");
      has_format = true;
    } else if (keyword == "element" && words.size() == 3) {
      Element element;
      element.name = words[1];
      element.line = number;
      if (!parse_integer(words[2], element.count) || element.count < 0)
        fail_at_line(file, number, "PLY element '" + element.name + "' has count '" + std::string(words[2]) +
                                       "', not a whole number");
      header.elements.push_back(element);
    } else if (keyword == "property" && !header.elements.empty() &&
               ((words.size() == 3 && words[1] != "list") || (words.size() == 5 && words[1] == "list"))) {
      header.elements.back().properties.push_back(read_property(words, file, number));
    } else {
      fail_at_line(file, number, "malformed PLY header line '" + std::string(line.substr(0, 80)) + "'");
    }
  }
  throw MeshError(file, "malformed or truncated PLY header (no end_header line)");
}

// What a property is to the mesh.
enum class Role { none, x, y, z, corners };

// Per element and property, its role; checks that the vertex element has x, y and z and the face element a list of
// integer vertex indices, and that no element with rows lacks properties.
std::vector<std::vector<Role>> find_roles(const Header& header, const std::string& file, long long& vertex_count) {
  std::vector<std::vector<Role>> roles;
  bool has_vertex = false, has_face = false;
  vertex_count = 0;
  for (const Element& element : header.elements) {
    roles.emplace_back(element.properties.size(), Role::none);
    std::vector<Role>& role = roles.back();
    if (element.count > 0 && element.properties.empty())
      fail_at_line(file, element.line, "PLY element '" + element.name + "' has rows but no properties");
    const auto find = [&](std::string_view name) {
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        if (element.properties[p].name == name) return static_cast<int>(p);
      }
      return -1;
    };
    if (element.name == "vertex") {
      if (has_vertex) fail_at_line(file, element.line, "a second PLY vertex element");
      has_vertex = true;
      if (element.count > INT_MAX)
        fail_at_line(file, element.line, "more vertices (" + std::to_string(element.count) + ") than clothcd can index");
      vertex_count = element.count;
      const std::pair<const char*, Role> axes[] = {{"x", Role::x}, {"y", Role::y}, {"z", Role::z}};
      for (const auto& [axis, axis_role] : axes) {
        const int p = find(axis);
        if (p < 0 || element.properties[static_cast<std::size_t>(p)].list)
          fail_at_line(file, element.line, std::string("PLY vertex element has no '") + axis + "' property");
        role[static_cast<std::size_t>(p)] = axis_role;
      }
    } else if (element.name == "face") {
      if (has_face) fail_at_line(file, element.line, "a second PLY face element");
      has_face = true;
      int p = find("vertex_indices");
      if (p < 0) p = find("vertex_index");
      if (p < 0 || !element.properties[static_cast<std::size_t>(p)].list) {
        if (element.count > 0) fail_at_line(file, element.line, "PLY face element has no vertex_indices list");
        continue;
      }
      if (!is_integer(element.properties[static_cast<std::size_t>(p)].type))
        fail_at_line(file, element.line, "PLY vertex indices of a floating-point type");
      role[static_cast<std::size_t>(p)] = Role::corners;
    }
  }
  return roles;
}

// Throws unless the rows declared fit in the body (each row at least its smallest size): a count is never trusted
// with memory before this.
void check_counts_fit(const Header& header, std::size_t body_bytes, const std::string& file) {
  const bool ascii = header.encoding == Encoding::ascii;
  const unsigned long long available = body_bytes + (ascii ? 1 : 0);  // the last ASCII line may lack its line end
  unsigned long long needed = 0;
  for (const Element& element : header.elements) {
    unsigned long long row = 0;  // ASCII: a digit and a separator per value; binary: the scalars and list counts
    for (const Property& property : element.properties)
      row += ascii ? 2 : scalar_bytes(property.list ? property.count_type : property.type);
    const auto count = static_cast<unsigned long long>(element.count);
    if (row > 0 && (count > available / row || needed + count * row > available))
      fail_at_line(file, element.line,
                   "PLY element '" + element.name + "' declares " + std::to_string(element.count) +
                       " rows, more than the " + std::to_string(body_bytes) +
                       " bytes of the body hold (truncated file or wrong count)");
    needed += count * row;
  }
}

// The row's element and number for messages ("PLY face 12").
std::string row_name(const Element& element, long long row) { return "PLY " + element.name + " " + std::to_string(row); }

void read_ascii_body(std::string_view bytes, const Header& header, const std::vector<std::vector<Role>>& roles,
                     long long vertex_count, const std::string& file, MeshBuilder& mesh) {
  LineCursor lines(bytes, header.body_start, header.body_line);
  std::vector<std::string_view> tokens;
  std::vector<int> corners;
  std::string_view line;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    for (long long row = 0; row < element.count; ++row) {
      tokens.clear();
      while (tokens.empty()) {
        if (!lines.next(line))
          throw MeshError(file, "PLY body ends at " + element.name + " " + std::to_string(row) + " of " +
                                    std::to_string(element.count) + " declared (truncated file or wrong count)");
        Tokens words(line);
        for (std::string_view word; words.next(word);) tokens.push_back(word);
      }
      const std::size_t at = lines.line_number();
      // The values the properties take: one per scalar, a list's count and its items.
      unsigned long long needed = 0;
      for (const Property& property : element.properties) {
        long long items = 0;
        if (property.list && needed < tokens.size() && parse_integer(tokens[needed], items) && items >= 0)
          needed += static_cast<unsigned long long>(std::min(items, 1LL << 40));
        ++needed;
      }
      if (tokens.size() != needed)
        fail_at_line(file, at, row_name(element, row) + " has " + std::to_string(tokens.size()) +
                                   " values, its properties need " + std::to_string(needed) +
                                   " (malformed line, or a truncated file or wrong count)");
      double position[3] = {0.0, 0.0, 0.0};
      std::size_t t = 0;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const Role role = roles[e][p];
        long long items = 1;
        if (property.list && (!parse_integer(tokens[t++], items) || items < 0))
          fail_at_line(file, at, row_name(element, row) + ": list length '" + std::string(tokens[t - 1]) + "' is not a whole number");
        if (role == Role::corners && items < 3)
          fail_at_line(file, at, row_name(element, row) + " has " + std::to_string(items) + " corners, a face needs 3 or more");
        corners.clear();
        for (long long k = 0; k < items; ++k, ++t) {
          const std::string_view token = tokens[t];
          if (role == Role::corners) {
            long long index = 0;
            if (!parse_integer(token, index) || index < 0 || index >= vertex_count)
              fail_at_line(file, at, row_name(element, row) + " has vertex index '" + std::string(token) +
                                         "', out of range 0.." + std::to_string(vertex_count - 1));
            corners.push_back(static_cast<int>(index));
            continue;
          }
          double value = 0.0;
          if (!parse_double(token, value))
            fail_at_line(file, at, row_name(element, row) + ": '" + std::string(token) + "' is not a number");
          if (role != Role::none) {
            if (!std::isfinite(value))
              fail_at_line(file, at, row_name(element, row) + ": non-finite coordinate '" + std::string(token) + "'");
            position[static_cast<int>(role) - 1] = value;
          }
        }
        if (role == Role::corners) mesh.add_polygon(corners.data(), corners.size());
      }
      if (element.name == "vertex") mesh.positions.insert(mesh.positions.end(), position, position + 3);
    }
  }
  while (lines.next(line)) {
    if (!Tokens(line).empty()) fail_at_line(file, lines.line_number(), "text after the last PLY element");
  }
}

// The next value of type `type`, converted to double (exact for every PLY type).
double read_value(ByteCursor& in, Scalar type) {
  switch (type) {
    case Scalar::int8: return static_cast<std::int8_t>(in.read_bits<1>());
    case Scalar::uint8: return static_cast<double>(in.read_bits<1>());
    case Scalar::int16: return static_cast<std::int16_t>(in.read_bits<2>());
    case Scalar::uint16: return static_cast<double>(in.read_bits<2>());
    case Scalar::int32: return static_cast<std::int32_t>(in.read_bits<4>());
    case Scalar::uint32: return static_cast<double>(in.read_bits<4>());
    case Scalar::float32: return float_from_bits(static_cast<std::uint32_t>(in.read_bits<4>()));
    case Scalar::float64: return double_from_bits(in.read_bits<8>());
  }
  return 0.0;
}

void read_binary_body(std::string_view bytes, const Header& header, const std::vector<std::vector<Role>>& roles,
                      long long vertex_count, const std::string& file, MeshBuilder& mesh) {
  ByteCursor in(bytes, header.body_start, header.encoding == Encoding::binary_big_endian, file);
  std::vector<int> corners;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const std::string what = "element '" + element.name + "'";
    const bool skipped_whole = element.name != "vertex" && element.name != "face" &&
                               std::none_of(element.properties.begin(), element.properties.end(),
                                            [](const Property& property) { return property.list; });
    if (skipped_whole) {  // fixed-size rows of no interest: skipped at once (the counts were checked to fit)
      std::size_t row = 0;
      for (const Property& property : element.properties) row += scalar_bytes(property.type);
      in.require(row * static_cast<std::size_t>(element.count), what);
      in.skip(row * static_cast<std::size_t>(element.count));
      continue;
    }
    for (long long row = 0; row < element.count; ++row) {
      double position[3] = {0.0, 0.0, 0.0};
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const Role role = roles[e][p];
        const std::size_t value_bytes = scalar_bytes(property.type);
        if (!property.list) {
          in.require(value_bytes, what);
          const std::size_t offset = in.position();
          const double value = read_value(in, property.type);
          if (role == Role::none) continue;
          if (!std::isfinite(value)) fail_at_byte(file, offset, row_name(element, row) + ": non-finite coordinate");
          position[static_cast<int>(role) - 1] = value;
          continue;
        }
        in.require(scalar_bytes(property.count_type), what);
        const std::size_t count_offset = in.position();
        const auto items = static_cast<long long>(read_value(in, property.count_type));
        if (items < 0) fail_at_byte(file, count_offset, row_name(element, row) + ": negative list length");
        in.require(static_cast<std::size_t>(items) * value_bytes, what);
        if (role != Role::corners) {
          in.skip(static_cast<std::size_t>(items) * value_bytes);
          continue;
        }
        if (items < 3)
          fail_at_byte(file, count_offset, row_name(element, row) + " has " + std::to_string(items) +
                                               " corners, a face needs 3 or more");
        corners.clear();
        for (long long k = 0; k < items; ++k) {
          const std::size_t offset = in.position();
          const auto index = static_cast<long long>(read_value(in, property.type));
          if (index < 0 || index >= vertex_count)
            fail_at_byte(file, offset, row_name(element, row) + " has vertex index " + std::to_string(index) +
                                           ", out of range 0.." + std::to_string(vertex_count - 1));
          corners.push_back(static_cast<int>(index));
        }
        mesh.add_polygon(corners.data(), corners.size());
      }
      if (element.name == "vertex") mesh.positions.insert(mesh.positions.end(), position, position + 3);
    }
  }
  if (in.remaining() > 0)
    fail_at_byte(file, in.position(), std::to_string(in.remaining()) +
                                          " bytes after the last PLY element (trailing bytes, or a wrong count)");
}

}  // namespace

TriangleMesh read_ply(std::string_view bytes, const std::string& file) {
  const Header header = read_header(bytes, file);
  check_counts_fit(header, bytes.size() - header.body_start, file);
  long long vertex_count = 0;
  const std::vector<std::vector<Role>> roles = find_roles(header, file, vertex_count);
  MeshBuilder mesh;
  mesh.positions.reserve(static_cast<std::size_t>(vertex_count) * 3);
  for (const Element& element : header.elements) {
    if (element.name == "face") mesh.triangles.reserve(static_cast<std::size_t>(element.count) * 3);
  }
  if (header.encoding == Encoding::ascii) {
    read_ascii_body(bytes, header, roles, vertex_count, file, mesh);
  } else {
    read_binary_body(bytes, header, roles, vertex_count, file, mesh);
  }
  return mesh.finish();
}

}  // namespace clothcd::detail
