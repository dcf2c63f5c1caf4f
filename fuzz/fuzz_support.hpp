#pragma once
// Helpers of the fuzz targets: the input as text, two files out of one input, a scratch folder, and the checks of what
// a reader returned. Every target accepts only the error types the reader documents; anything else (another
// exception, a crash, a sanitizer report, a mesh that breaks its invariants) is a finding.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::fuzz {

/// The line that separates the two files of a two-file input.
inline constexpr std::string_view kFileSeparator = "\n==> next file <==\n";

/// The input split at the first kFileSeparator (the second part is empty without one).
inline std::pair<std::string, std::string> split_files(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t at = input.find(kFileSeparator);
  if (at == std::string_view::npos) return {std::string(input), std::string()};
  return {std::string(input.substr(0, at)), std::string(input.substr(at + kFileSeparator.size()))};
}

/// A folder removed with everything in it when the process exits normally.
struct ScratchDir {
  std::filesystem::path path;  ///< The folder.
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

/// A folder of this process's own in memory (/dev/shm) when possible, else under the temp dir (created once).
inline const std::filesystem::path& scratch_dir() {
  static const ScratchDir dir{[] {
    std::error_code error;
    const bool shm = std::filesystem::is_directory("/dev/shm", error) && access("/dev/shm", W_OK) == 0;
    auto path = (shm ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path()) /
                ("clothcd-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(path);
    return path;
  }()};
  return dir.path;
}

/// Writes `contents` to `name` in the scratch folder and returns its path.
inline std::filesystem::path scratch_file(const std::string& name, const std::string& contents) {
  const auto path = scratch_dir() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << contents;
  return path;
}

/// Aborts (a finding) unless every coordinate is finite and every index names a vertex.
inline void require_valid(const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite()) std::abort();
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) {
    if (mesh.faces.data()[i] < 0 || mesh.faces.data()[i] >= mesh.vertex_count()) std::abort();
  }
}

}  // namespace clothcd::fuzz
