// Output path checks (output_paths.hpp).
#include "output_paths.hpp"

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace clothcd::cli {

namespace fs = std::filesystem;

void check_output_file(const std::string& path, const std::string& option, const std::vector<std::string>& extensions) {
  const std::string prefix = option + " " + path + ": ";
  if (path.empty()) throw std::runtime_error(option + ": empty path");
  std::error_code error;
  if (fs::is_directory(path, error)) throw std::runtime_error(prefix + "is a folder, not a file");
  if (!extensions.empty()) {
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    bool known = false;
    std::string names;
    for (const std::string& e : extensions) {
      known = known || extension == e;
      names += (names.empty() ? "" : ", ") + e;
    }
    if (!known) throw std::runtime_error(prefix + "unknown file type '" + extension + "' (known: " + names + ")");
  }
  const fs::path folder = fs::path(path).parent_path();
  const fs::path existing = folder.empty() ? fs::path(".") : folder;
  if (!fs::is_directory(existing, error))
    throw std::runtime_error(prefix + "cannot open for writing (no folder " + existing.string() + ")");
  if (access(existing.c_str(), W_OK) != 0)
    throw std::runtime_error(prefix + "cannot open for writing (folder " + existing.string() + " is not writable)");
}

void create_output_folder(const std::string& path, const std::string& option) {
  const std::string prefix = option + " " + path + ": ";
  if (path.empty()) throw std::runtime_error(option + ": empty path");
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error)) throw std::runtime_error(prefix + "is a file, not a folder");
  fs::create_directories(path, error);
  if (error) throw std::runtime_error(prefix + "cannot create the folder (" + error.message() + ")");
  if (access(path.c_str(), W_OK) != 0) throw std::runtime_error(prefix + "the folder is not writable");
}

}  // namespace clothcd::cli
