// `clothcd meshes`: put the paper's obstacle models from Debian packages into the cache folder, with an index.
#include <fstream>
#include <iostream>
#include <string>

#include "clothcd/mesh/model_catalog.hpp"
#include "commands.hpp"

namespace clothcd::cli {

void add_meshes_command(CLI::App& app) {
  auto* command = app.add_subcommand("meshes", "Fetch the obstacle models into the cache folder and print its index");
  auto dir = std::make_shared<std::string>(default_model_dir().string());
  command->add_option("--dir", *dir, "Cache folder ($CLOTHCD_MODEL_DIR or .cache/models)")->capture_default_str();
  command->callback([dir] {
    const auto index = fetch_all_models(*dir);
    std::ifstream in(index);
    std::cout << in.rdbuf();
    std::cout << "index: " << index.string() << '\n';
  });
}

}  // namespace clothcd::cli
