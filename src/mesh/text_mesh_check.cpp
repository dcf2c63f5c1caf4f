// Checks of OFF and PLY bodies (see text_mesh_check.hpp).
#include "mesh/text_mesh_check.hpp"

#include <cerrno>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <string>
#include <vector>

#include "clothcd/mesh/mesh_error.hpp"

namespace clothcd::detail {
namespace {

// The next non-empty line without its # comment, split into tokens; false at the end of the file.
bool next_tokens(std::istream& in, std::vector<std::string>& tokens) {
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    tokens.clear();
    for (std::string word; words >> word;) tokens.push_back(word);
    if (!tokens.empty()) return true;
  }
  return false;
}

// The whole number a token holds, or -1 when it holds none (or one beyond 2^62).
long long whole_number(const std::string& token) {
  if (token.empty() || token.find_first_not_of("+-0123456789") != std::string::npos) return -1;
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (errno != 0 || end != token.c_str() + token.size() || value < 0 || value > (1LL << 62)) return -1;
  return value;
}

// Throws when a coordinate token has more integer digits than assimp's text readers convert (from 20 digits, about
// 2^64, they silently read 0): such a number must be written with an exponent.
void check_coordinate(const std::string& token, const std::string& file, const std::string& where) {
  std::size_t begin = token.find_first_not_of("+-");
  if (begin == std::string::npos) return;
  begin = token.find_first_not_of('0', begin);
  if (begin == std::string::npos) return;
  const std::size_t end = token.find_first_not_of("0123456789", begin);
  const std::size_t digits = (end == std::string::npos ? token.size() : end) - begin;
  if (digits >= 20)
    throw MeshError(file, where + ": coordinate '" + token + "' has " + std::to_string(digits) +
                              " integer digits, more than the reader converts (write it with an exponent)");
}

// Bytes of a PLY scalar type, 0 for an unknown name.
int ply_type_bytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

}  // namespace

void check_off_body(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> tokens;
  if (!next_tokens(in, tokens) || tokens[0] != "OFF") return;  // not plain OFF: assimp decides
  const std::string file = path.string();
  tokens.erase(tokens.begin());  // the counts may follow OFF on its line
  if (tokens.empty() && !next_tokens(in, tokens)) throw MeshError(file, "OFF file ends before its counts");
  const long long vertices = whole_number(tokens[0]);
  const long long faces = tokens.size() > 1 ? whole_number(tokens[1]) : -1;
  if (vertices < 0 || faces < 0) throw MeshError(file, "OFF counts are not whole numbers >= 0");
  for (long long v = 0; v < vertices; ++v) {
    if (!next_tokens(in, tokens) || tokens.size() < 3)
      throw MeshError(file, "OFF file ends (or a vertex line is short) at vertex " + std::to_string(v) + " of " +
                                std::to_string(vertices) + " declared (truncated file or wrong count)");
    for (const std::string& token : tokens) check_coordinate(token, file, "OFF vertex " + std::to_string(v));
  }
  for (long long f = 0; f < faces; ++f) {
    if (!next_tokens(in, tokens))
      throw MeshError(file, "OFF file ends at face " + std::to_string(f) + " of " + std::to_string(faces) +
                                " declared (truncated file or wrong count)");
    const long long corners = whole_number(tokens[0]);
    if (corners < 3) throw MeshError(file, "OFF face " + std::to_string(f) + " has " + tokens[0] + " vertices, a face needs 3 or more");
    if (static_cast<long long>(tokens.size()) < corners + 1)
      throw MeshError(file, "OFF face " + std::to_string(f) + " lists fewer than its " + tokens[0] + " vertex indices");
    for (long long k = 1; k <= corners; ++k) {
      const long long index = whole_number(tokens[static_cast<std::size_t>(k)]);
      if (index < 0 || index >= vertices)
        throw MeshError(file, "OFF face " + std::to_string(f) + " has vertex index '" + tokens[static_cast<std::size_t>(k)] +
                                  "', out of range 0.." + std::to_string(vertices - 1));
    }
  }
}

void check_ply_body(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return;
  const std::string file = path.string();
  struct Element {
    std::string name;
    long long count = 0;
    std::vector<bool> is_list;  // per property: a list (count, then items) or one scalar
    std::vector<std::string> scalars;  // names of the scalar properties
  };
  std::vector<Element> elements;
  double least_bytes = 0.0;  // binary: the smallest body the header allows (each list at least its count)
  bool ascii = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string name;
      words >> name;
      ascii = name == "ascii";
    } else if (keyword == "element") {
      Element element;
      std::string count;
      words >> element.name >> count;
      element.count = whole_number(count);
      if (element.count < 0)
        throw MeshError(file, "PLY element '" + element.name + "' has count '" + count + "', not a whole number");
      elements.push_back(element);
    } else if (keyword == "property") {
      if (elements.empty()) throw MeshError(file, "PLY property before any element");
      std::string type;
      words >> type;
      const bool list = type == "list";
      if (list) words >> type;  // the list's count type: what every list holds at least
      const int bytes = ply_type_bytes(type);
      if (bytes == 0) throw MeshError(file, "PLY property type '" + type + "' is unknown");
      elements.back().is_list.push_back(list);
      std::string name;
      if (!list && words >> name) elements.back().scalars.push_back(name);
      least_bytes += static_cast<double>(elements.back().count) * bytes;
    } else if (keyword == "end_header") {
      break;
    }
  }
  // Without x, y and z the reader puts every vertex at the origin.
  for (const Element& element : elements) {
    if (element.name != "vertex" || element.count == 0) continue;
    for (const char* axis : {"x", "y", "z"}) {
      if (std::find(element.scalars.begin(), element.scalars.end(), axis) == element.scalars.end())
        throw MeshError(file, std::string("PLY vertex element has no '") + axis + "' property");
    }
  }
  if (ascii) {
    // One line per element, holding exactly its properties' values (a list: its count, then that many items).
    std::vector<std::string> tokens;
    for (const Element& element : elements) {
      for (long long row = 0; row < element.count; ++row) {
        const std::string where = "PLY " + element.name + " " + std::to_string(row);
        if (!next_tokens(in, tokens))
          throw MeshError(file, "PLY body ends at " + element.name + " " + std::to_string(row) + " of " +
                                    std::to_string(element.count) + " declared (truncated file or wrong count)");
        std::size_t needed = 0;
        for (const bool list : element.is_list) {
          if (list && needed < tokens.size()) {
            const long long items = whole_number(tokens[needed]);
            if (items < 0) throw MeshError(file, where + ": list length '" + tokens[needed] + "' is not a whole number");
            needed += static_cast<std::size_t>(std::min<long long>(items, 1LL << 40));
          }
          ++needed;
        }
        if (tokens.size() != needed)
          throw MeshError(file, where + " has " + std::to_string(tokens.size()) + " values, its properties need " +
                                    std::to_string(needed) + " (malformed line, or a truncated file or wrong count)");
        for (const std::string& token : tokens) check_coordinate(token, file, where);
      }
    }
    return;
  }
  const std::streamoff body_start = in.tellg();
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error || body_start < 0) return;  // assimp reports what it cannot read
  const double body = static_cast<double>(size) - static_cast<double>(body_start);
  if (body < least_bytes)
    throw MeshError(file, "binary PLY body holds " + std::to_string(static_cast<long long>(body)) +
                              " bytes, its header declares at least " + std::to_string(least_bytes) +
                              " (truncated file or wrong count)");
}

void check_obj_numbers(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  long long vertex = 0;
  while (std::getline(in, line)) {
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    ++vertex;
    std::istringstream words(line.substr(1));
    for (std::string token; words >> token;)
      check_coordinate(token, path.string(), "OBJ vertex " + std::to_string(vertex));
  }
}

std::vector<long long> obj_face_vertices(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<long long> corners;
  std::string line;
  long long vertices = 0;
  while (std::getline(in, line)) {
    if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
    if (line[0] == 'v') ++vertices;
    if (line[0] != 'f') continue;
    std::istringstream words(line.substr(1));
    for (std::string token; words >> token;) {
      const std::string number = token.substr(0, token.find('/'));
      char* end = nullptr;
      long long value = std::strtoll(number.c_str(), &end, 10);
      if (number.empty() || end != number.c_str() + number.size()) value = 0;
      corners.push_back(value < 0 ? vertices + 1 + value : value);
    }
  }
  return corners;
}

void check_ase_header(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string first;
  in >> first;
  if (first != "*3DSMAX_ASCIIEXPORT")
    throw MeshError(path.string(), "not an ASE file (it does not start with *3DSMAX_ASCIIEXPORT)");
}

}  // namespace clothcd::detail
