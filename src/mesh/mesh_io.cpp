// Mesh reading through assimp (every format it knows) and OBJ / ASCII PLY writing at full double precision.
// Our own writers exist because assimp's exporters go through its float vertex type and would round coordinates.
#include "clothcd/mesh/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <mutex>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <unordered_map>
#include <vector>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_validation.hpp"
#include "mesh/text_mesh_check.hpp"

namespace clothcd {
namespace {

namespace fs = std::filesystem;

void check_readable_file(const fs::path& path) {
  std::error_code error;
  const auto status = fs::status(path, error);
  if (!fs::exists(status)) throw MeshError(path.string(), "no such file");
  if (fs::is_directory(status)) throw MeshError(path.string(), "is a directory, not a mesh file");
  if (fs::file_size(path, error) == 0) throw MeshError(path.string(), "the file is empty");
}

/// assimp 5.2's PLY reader loops forever on a header cut short: make sure a PLY header ends before assimp sees it.
void check_ply_header(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.rfind("ply", 0) != 0) return;
  if (head.find("\nend_header") == std::string::npos) {
    throw MeshError(path.string(), "malformed or truncated PLY header (no end_header line)");
  }
}

/// Collects the error messages assimp logs. Some readers log a problem and repair it silently (the OFF reader clamps
/// out-of-range indices, for one); a mesh that needed such a repair is rejected rather than used wrongly.
class ErrorCollector : public Assimp::LogStream {
 public:
  void write(const char* message) override {
    if (first_error_.empty()) first_error_ = message;
    while (!first_error_.empty() && (first_error_.back() == '\n' || first_error_.back() == '\r')) first_error_.pop_back();
  }
  [[nodiscard]] const std::string& first_error() const { return first_error_; }

 private:
  std::string first_error_;
};

/// assimp's logger is process-wide: imports are serialized so each one sees only its own errors.
std::mutex& import_mutex() {
  static std::mutex mutex;
  return mutex;
}

/// Installs the error collector as assimp's logger for the lifetime of one import.
class ScopedErrorLog {
 public:
  ScopedErrorLog() {
    Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(&collector_, Assimp::Logger::Err);
  }
  ~ScopedErrorLog() {
    Assimp::DefaultLogger::get()->detachStream(&collector_, Assimp::Logger::Err);
    Assimp::DefaultLogger::kill();
  }
  ScopedErrorLog(const ScopedErrorLog&) = delete;
  ScopedErrorLog& operator=(const ScopedErrorLog&) = delete;
  [[nodiscard]] const std::string& first_error() const { return collector_.first_error(); }

 private:
  ErrorCollector collector_;
};

void reject_faces_without_indices(const aiScene& scene, const fs::path& path) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      if (mesh.mFaces[f].mNumIndices == 0) {
        throw MeshError(path.string(), "malformed or truncated mesh file (face " + std::to_string(f) + " has no vertices)");
      }
    }
  }
}

// The file name's extension in lower case (".obj").
std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension;
}

// An OFF file with # comments, without them (assimp's OFF reader loses the faces after a comment line between the
// vertices and the faces); empty for any other file.
std::string uncommented_off(const fs::path& path) {
  if (lower_extension(path) != ".off") return {};
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find('#') == std::string::npos) return {};
  std::string out;
  out.reserve(text.size());
  bool comment = false;
  for (const char c : text) {
    if (c == '#') comment = true;
    if (c == '\n') comment = false;
    if (!comment) out.push_back(c);
  }
  return out;
}

const aiScene* import_scene(Assimp::Importer& importer, const fs::path& path, const ScopedErrorLog& log) {
  // Points and lines are not surfaces: drop them, keep triangles (polygons are triangulated).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read and validate first, post-process second: assimp's triangulation aborts the process (an assertion, not an
  // error) on faces without indices, which some readers produce from truncated files.
  const aiScene* scene = nullptr;
  const std::string off_text = uncommented_off(path);
  if (!off_text.empty()) {
    scene = importer.ReadFileFromMemory(off_text.data(), off_text.size(), aiProcess_ValidateDataStructure, "off");
  } else {
    scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  }
  if (scene != nullptr) reject_faces_without_indices(*scene, path);
  if (scene != nullptr) {
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  }
  if (scene == nullptr) {
    std::string reason = importer.GetErrorString();
    if (reason.empty()) reason = "unknown error";
    throw MeshError(path.string(), "cannot be read as a mesh (" + reason + ")");
  }
  if (!log.first_error().empty()) {
    throw MeshError(path.string(), "malformed mesh file (the reader reported: " + log.first_error() + ")");
  }
  return scene;
}

/// Appends the triangles of every mesh of the scene; vertex indices are offset per mesh.
TriangleMesh collect_triangles(const aiScene& scene, LoadReport& report) {
  std::size_t vertex_total = 0, face_total = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    vertex_total += scene.mMeshes[m]->mNumVertices;
    for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f) face_total += scene.mMeshes[m]->mFaces[f].mNumIndices == 3;
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertex_total), 3);
  mesh.faces.resize(static_cast<Eigen::Index>(face_total), 3);
  Eigen::Index v_out = 0, f_out = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& source = *scene.mMeshes[m];
    const auto offset = static_cast<int>(v_out);
    for (unsigned v = 0; v < source.mNumVertices; ++v, ++v_out) {
      mesh.vertices.row(v_out) << source.mVertices[v].x, source.mVertices[v].y, source.mVertices[v].z;
    }
    for (unsigned f = 0; f < source.mNumFaces; ++f) {
      const aiFace& face = source.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int c = 0; c < 3; ++c) mesh.faces(f_out, c) = offset + static_cast<int>(face.mIndices[c]);
      ++f_out;
    }
  }
  report.source_meshes = static_cast<int>(scene.mNumMeshes);
  return mesh;
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

void save_obj(const TriangleMesh& mesh, std::ofstream& out) {
  out.precision(17);
  out << "# written by clothcd\n";
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) {
    out << "v " << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << '\n';
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    out << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1 << '\n';
  }
}

// ASCII, not binary: assimp 5.2's binary PLY reader skips whitespace after "end_header", so a file whose first data
// byte happens to be 0x0a or 0x20 (sin(pi/16) as a little-endian double starts with 0x0a) is read shifted by a byte.
void save_ascii_ply(const TriangleMesh& mesh, std::ofstream& out) {
  out.precision(17);
  out << "ply\nformat ascii 1.0\ncomment written by clothcd\n"
      << "element vertex " << mesh.vertex_count() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << mesh.face_count() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) {
    out << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << '\n';
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    out << "3 " << mesh.faces(f, 0) << ' ' << mesh.faces(f, 1) << ' ' << mesh.faces(f, 2) << '\n';
  }
}

}  // namespace

TriangleMesh load_mesh(const fs::path& path, const LoadOptions& options, LoadReport* report) {
  check_readable_file(path);
  check_ply_header(path);
  detail::check_off_body(path);
  detail::check_ply_body(path);
  if (lower_extension(path) == ".obj") detail::check_obj_numbers(path);
  if (lower_extension(path) == ".ase") detail::check_ase_header(path);
  LoadReport local_report;
  const std::lock_guard<std::mutex> lock(import_mutex());
  const ScopedErrorLog log;
  Assimp::Importer importer;
  const aiScene* scene = import_scene(importer, path, log);
  TriangleMesh mesh = collect_triangles(*scene, local_report);
  if (mesh.face_count() == 0) throw MeshError(path.string(), "the file holds no triangles");
  validate_mesh(mesh, path.string());
  if (options.join_identical_vertices) join_identical_vertices(mesh, local_report);
  if (options.drop_degenerate_faces) {
    local_report.degenerate_faces_dropped = drop_degenerate_faces(mesh);
    if (mesh.face_count() == 0) throw MeshError(path.string(), "every face is degenerate (zero area)");
  }
  if (report != nullptr) *report = local_report;
  return mesh;
}

void save_mesh(const TriangleMesh& mesh, const fs::path& path) {
  const std::string extension = lower_extension(path);
  if (extension != ".obj" && extension != ".ply") {
    throw MeshError(path.string(), "unsupported output format '" + extension + "' (use .obj or .ply)");
  }
  if (!mesh.vertices.allFinite()) throw MeshError(path.string(), "not written: a coordinate is NaN or infinite");
  if (mesh.face_count() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertex_count()))
    throw MeshError(path.string(), "not written: a face index is outside 0.." + std::to_string(mesh.vertex_count() - 1));
  std::ofstream out(path, std::ios::binary);
  if (!out) throw MeshError(path.string(), "cannot be opened for writing");
  if (extension == ".obj") {
    save_obj(mesh, out);
  } else {
    save_ascii_ply(mesh, out);
  }
  out.close();
  if (!out) throw MeshError(path.string(), "write failed");
}

}  // namespace clothcd
