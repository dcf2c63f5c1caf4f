#pragma once
// Helpers shared by the tests: a self-deleting temporary folder, small file writers, and running the clothcd program.

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace clothcd::test {

/// A fresh folder under the system temp dir, removed with everything in it when the object dies.
class TempDir {
 public:
  TempDir() {
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() / ("clothcd-test-" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The folder.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// A path inside the folder.
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Writes `contents` to `path` byte for byte and returns the path.
inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& contents) {
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

/// The whole contents of a file ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The outcome of running the clothcd program.
struct CliRun {
  int exit_code = -1;  ///< Exit status.
  std::string output;  ///< stdout and stderr together.
};

/// Runs `clothcd <arguments>` (arguments are passed to the shell as written) and captures its output.
/// With `stdout_only`, stderr is discarded instead.
inline CliRun run_cli(const std::string& arguments, bool stdout_only = false) {
  const std::string command = std::string("'") + CLOTHCD_CLI_PATH + "' " + arguments + (stdout_only ? " 2>/dev/null" : " 2>&1");
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) run.output.append(buffer, got);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

/// The cache folder the tests fetch the Debian-package models into (shared by test runs, under the build tree).
inline std::filesystem::path test_model_dir() {
  return std::filesystem::path(CLOTHCD_TEST_MODEL_DIR);
}

}  // namespace clothcd::test
