// OBJ and PLY writing (see mesh_io.hpp). Coordinates are written as the shortest decimal that reads back as the same
// double (std::to_chars), or as the double's bytes in binary PLY, so a write and a read give the same bits.
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd {
namespace {

namespace fs = std::filesystem;

void append_number(std::string& out, double value) {
  std::array<char, 32> digits;
  const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
  out.append(digits.data(), result.ptr);
}

void append_number(std::string& out, Eigen::Index value) { out += std::to_string(value); }

// "<prefix>a b c\n" with the three values of a row.
template <typename Row>
void append_row(std::string& out, const char* prefix, const Row& row) {
  out += prefix;
  for (int c = 0; c < 3; ++c) {
    if (c > 0) out += ' ';
    append_number(out, row(c));
  }
  out += '\n';
}

std::string obj_text(const TriangleMesh& mesh) {
  std::string out = "# written by clothcd\n";
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) append_row(out, "v ", mesh.vertices.row(v));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) append_row(out, "f ", mesh.faces.row(f).cast<Eigen::Index>().array() + 1);
  return out;
}

std::string ply_header(const TriangleMesh& mesh, const char* format) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment written by clothcd\nelement vertex " +
         std::to_string(mesh.vertex_count()) + "\nproperty double x\nproperty double y\nproperty double z\n" +
         "element face " + std::to_string(mesh.face_count()) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string ascii_ply(const TriangleMesh& mesh) {
  std::string out = ply_header(mesh, "ascii");
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) append_row(out, "", mesh.vertices.row(v));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) append_row(out, "3 ", mesh.faces.row(f).cast<Eigen::Index>());
  return out;
}

// Appends the low `Size` bytes of `bits`, least significant first.
template <int Size>
void append_little_endian(std::string& out, std::uint64_t bits) {
  for (int i = 0; i < Size; ++i) out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

std::string binary_ply(const TriangleMesh& mesh) {
  std::string out = ply_header(mesh, "binary_little_endian");
  out.reserve(out.size() + static_cast<std::size_t>(mesh.vertex_count()) * 24 + static_cast<std::size_t>(mesh.face_count()) * 13);
  for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, mesh.vertices.data() + i, sizeof bits);
    append_little_endian<8>(out, bits);
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    out += static_cast<char>(3);
    for (int c = 0; c < 3; ++c) append_little_endian<4>(out, static_cast<std::uint32_t>(mesh.faces(f, c)));
  }
  return out;
}

}  // namespace

void save_mesh(const TriangleMesh& mesh, const fs::path& path, PlyEncoding ply) {
  const std::string extension = detail::lower_extension(path);
  if (extension != ".obj" && extension != ".ply") {
    throw MeshError(path.string(), "unsupported output format '" + extension + "' (use .obj or .ply)");
  }
  if (!mesh.vertices.allFinite()) throw MeshError(path.string(), "not written: a coordinate is NaN or infinite");
  if (mesh.face_count() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertex_count()))
    throw MeshError(path.string(), "not written: a face index is outside 0.." + std::to_string(mesh.vertex_count() - 1));
  const std::string bytes = extension == ".obj"              ? obj_text(mesh)
                            : ply == PlyEncoding::ascii      ? ascii_ply(mesh)
                                                             : binary_ply(mesh);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw MeshError(path.string(), "cannot be opened for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw MeshError(path.string(), "write failed");
}

}  // namespace clothcd
