// Reading the formats the project has no reader of its own for (3DS, BLEND, DAE, glTF, ASE, ...) through assimp,
// which stores coordinates as float. OBJ, PLY, OFF and STL never come here (see mesh_io.cpp).
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <fstream>
#include <mutex>
#include <string>

#include "clothcd/mesh/mesh_error.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd::detail {
namespace {

namespace fs = std::filesystem;

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

// Throws unless an ASE file starts with *3DSMAX_ASCIIEXPORT (assimp's ASE reader turns any text, "hello world"
// included, into an 8-face mesh at the origin).
void check_ase_header(const fs::path& path) {
  std::ifstream in(path);
  std::string first;
  in >> first;
  if (first != "*3DSMAX_ASCIIEXPORT")
    throw MeshError(path.string(), "not an ASE file (it does not start with *3DSMAX_ASCIIEXPORT)");
}

const aiScene* import_scene(Assimp::Importer& importer, const fs::path& path, const ScopedErrorLog& log) {
  // Points and lines are not surfaces: drop them, keep triangles (polygons are triangulated).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read and validate first, post-process second: assimp's triangulation aborts the process (an assertion, not an
  // error) on faces without indices, which some readers produce from truncated files.
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
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
TriangleMesh collect_triangles(const aiScene& scene, int& source_meshes) {
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
  source_meshes = static_cast<int>(scene.mNumMeshes);
  return mesh;
}

}  // namespace

TriangleMesh read_with_assimp(const fs::path& path, const std::string& extension, int& source_meshes) {
  const std::lock_guard<std::mutex> lock(import_mutex());
  Assimp::Importer importer;
  // Only readers chosen by the extension: assimp would otherwise guess from the contents, and could hand an OBJ, PLY,
  // OFF or STL file under another name to its own (float) reader of that format.
  if (extension.empty() || !importer.IsExtensionSupported(extension))
    throw MeshError(path.string(), "cannot be read as a mesh (unknown format '" + extension + "')");
  if (extension == ".ase") check_ase_header(path);
  const ScopedErrorLog log;
  const aiScene* scene = import_scene(importer, path, log);
  TriangleMesh mesh = collect_triangles(*scene, source_meshes);
  if (mesh.face_count() == 0) throw MeshError(path.string(), "the file holds no triangles");
  return mesh;
}

}  // namespace clothcd::detail
