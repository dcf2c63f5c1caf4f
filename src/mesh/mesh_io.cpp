// Mesh reading: OBJ, PLY, OFF and STL by the project's own readers (coordinates kept as the file's doubles), every
// other format through assimp; then validation, joining of identical positions and dropping of zero-area faces.
#include "clothcd/mesh/mesh_io.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_validation.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd {

std::string detail::lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension;
}

namespace {

namespace fs = std::filesystem;

// The file's size, after checking that it exists, is not a folder and is not empty.
std::uintmax_t checked_file_size(const fs::path& path) {
  std::error_code error;
  const auto status = fs::status(path, error);
  if (!fs::exists(status)) throw MeshError(path.string(), "no such file");
  if (fs::is_directory(status)) throw MeshError(path.string(), "is a directory, not a mesh file");
  const auto size = fs::file_size(path, error);
  if (error) throw MeshError(path.string(), "cannot be read (" + error.message() + ")");
  if (size == 0) throw MeshError(path.string(), "the file is empty");
  return size;
}

// The whole file (see checked_file_size).
std::string read_file_bytes(const fs::path& path) {
  const std::uintmax_t size = checked_file_size(path);
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size)) || in.gcount() != static_cast<std::streamsize>(size))
    throw MeshError(path.string(), "cannot be read (the read failed or the file shrank)");
  return bytes;
}

/// Merges vertices with bit-identical coordinates and drops vertices no face uses.
void join_identical_vertices(TriangleMesh& mesh, LoadReport& report) {
  struct KeyHash {
    std::size_t operator()(const std::array<std::uint64_t, 3>& k) const {
      return std::hash<std::uint64_t>()(k[0] * 0x9E3779B97F4A7C15ull ^ (k[1] + 0x632BE59BD9B4E019ull) * 31 ^ k[2]);
    }
  };
  std::unordered_map<std::array<std::uint64_t, 3>, int, KeyHash> first_index;
  first_index.reserve(static_cast<std::size_t>(mesh.vertex_count()));
  std::vector<int> remap(static_cast<std::size_t>(mesh.vertex_count()), -1);
  std::vector<bool> used(remap.size(), false);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    for (int c = 0; c < 3; ++c) used[static_cast<std::size_t>(mesh.faces(f, c))] = true;
  }
  Vertices joined(mesh.vertex_count(), 3);
  int next = 0;
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) {
    if (!used[static_cast<std::size_t>(v)]) continue;
    std::array<std::uint64_t, 3> key{};
    for (int c = 0; c < 3; ++c) {
      const double value = mesh.vertices(v, c) == 0.0 ? 0.0 : mesh.vertices(v, c);  // -0 and +0 are one position
      std::memcpy(&key[static_cast<std::size_t>(c)], &value, sizeof(double));
    }
    const auto [it, inserted] = first_index.emplace(key, next);
    if (inserted) joined.row(next++) = mesh.vertices.row(v);
    remap[static_cast<std::size_t>(v)] = it->second;
  }
  report.vertices_joined = static_cast<int>(std::count(used.begin(), used.end(), true)) - next;
  joined.conservativeResize(next, 3);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    for (int c = 0; c < 3; ++c) mesh.faces(f, c) = remap[static_cast<std::size_t>(mesh.faces(f, c))];
  }
  mesh.vertices = std::move(joined);
}

// The file's triangles as its reader gives them, validated.
TriangleMesh read_mesh_file(const fs::path& path, int& source_meshes) {
  const std::string extension = detail::lower_extension(path);
  const std::string file = path.string();
  source_meshes = 1;
  TriangleMesh mesh;
  if (extension == ".obj" || extension == ".ply" || extension == ".off" || extension == ".stl") {
    const std::string bytes = read_file_bytes(path);
    if (extension == ".obj") mesh = detail::read_obj(bytes, file);
    if (extension == ".ply") mesh = detail::read_ply(bytes, file);
    if (extension == ".off") mesh = detail::read_off(bytes, file);
    if (extension == ".stl") mesh = detail::read_stl(bytes, file);
  } else {
    (void)checked_file_size(path);
    mesh = detail::read_with_assimp(path, extension, source_meshes);
  }
  validate_mesh(mesh, file);
  return mesh;
}

}  // namespace

TriangleMesh load_mesh(const fs::path& path, const LoadOptions& options, LoadReport* report) {
  LoadReport local_report;
  TriangleMesh mesh = read_mesh_file(path, local_report.source_meshes);
  if (options.join_identical_vertices) join_identical_vertices(mesh, local_report);
  if (options.drop_degenerate_faces) {
    local_report.degenerate_faces_dropped = drop_degenerate_faces(mesh);
    if (mesh.face_count() == 0) throw MeshError(path.string(), "every face is degenerate (zero area)");
  }
  if (report != nullptr) *report = local_report;
  return mesh;
}

}  // namespace clothcd
