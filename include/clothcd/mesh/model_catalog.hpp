#pragma once
/// @file
/// The obstacle models of the paper's experiments, taken from Debian packages into a local cache folder.

#include <filesystem>
#include <string>
#include <vector>

namespace clothcd {

/// One model of the catalog and where it comes from.
struct ModelSource {
  std::string name;         ///< Catalog name used on the command line, e.g. "rabbit".
  std::string role;         ///< What it stands for in the paper, e.g. "rabbit (Stanford bunny)".
  std::string package;      ///< Debian package that ships it, or "generated".
  std::string licence;      ///< Licence of the file as the package states it.
  std::string origin;       ///< Absolute path of the file, or "data.tar.gz:<member>" inside libcgal-demo's archive.
  std::string cached_file;  ///< File name inside the cache folder.
};

/// Every model of the catalog: rabbit, cat, dinosaur, human, human-blend, cow, bird, sphere, cube, fish.
[[nodiscard]] const std::vector<ModelSource>& model_catalog();

/// The obstacle model cache folder: $CLOTHCD_CACHE when set (its old name $CLOTHCD_MODEL_DIR is still read), else
/// the user's cache folder: $XDG_CACHE_HOME/clothcd, or ~/.cache/clothcd without it.
[[nodiscard]] std::filesystem::path default_model_dir();

/// Returns the path of model `name` in `cache_dir`, copying or extracting it from its package first when missing.
/// Throws std::runtime_error when the name is unknown or the package is not installed (naming the package).
std::filesystem::path fetch_model(const std::string& name, const std::filesystem::path& cache_dir);

/// Fetches every model and writes `index.csv` (name, role, file, package, licence, vertices, faces) in `cache_dir`.
/// Returns the index path.
std::filesystem::path fetch_all_models(const std::filesystem::path& cache_dir);

}  // namespace clothcd
