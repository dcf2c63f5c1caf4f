#pragma once
// Checks of output paths made before a command starts its work, so that a bad path fails at once with a clear
// message instead of after minutes of computing.

#include <string>
#include <vector>

namespace clothcd::cli {

/// The mesh formats the writers produce (save_mesh).
inline const std::vector<std::string> kMeshOutputExtensions{".obj", ".ply"};

/// Throws std::runtime_error unless `path` can be created as a file: not a folder, its folder exists, and, when
/// `extensions` is not empty, it ends with one of them in any case (".obj", ".OBJ"). `option` names it in the message ("--out").
void check_output_file(const std::string& path, const std::string& option,
                       const std::vector<std::string>& extensions = {});

/// Creates the folder `path` (and its parents) or throws std::runtime_error saying why it cannot.
void create_output_folder(const std::string& path, const std::string& option);

}  // namespace clothcd::cli
