// `clothcd meshes`: put the paper's obstacle models from Debian packages into the cache folder, with an index.
#include <fstream>
#include <iostream>
#include <string>

#include "clothcd/mesh/model_catalog.hpp"
#include "commands.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct MeshesOptions {
  std::string cache;
  bool json = false;
};

void run_meshes(const MeshesOptions& options) {
  const auto index = fetch_all_models(options.cache);
  if (options.json) {
    Json report = json_report("meshes");
    report["cache"] = options.cache;
    report["index"] = index.string();
    Json models = Json::array();
    for (const ModelSource& model : model_catalog())
      models.push_back({{"name", model.name},
                        {"role", model.role},
                        {"file", (std::filesystem::path(options.cache) / model.cached_file).string()},
                        {"package", model.package},
                        {"licence", model.licence}});
    report["models"] = std::move(models);
    print_json(report);
    return;
  }
  std::ifstream in(index);
  std::cout << in.rdbuf();
  std::cout << "index: " << index.string() << '\n';
}

}  // namespace

void add_meshes_command(CLI::App& app) {
  auto* command = app.add_subcommand("meshes", "Fetch the obstacle models into the cache folder and print its index");
  auto options = std::make_shared<MeshesOptions>();
  add_cache_option(*command, options->cache, "--dir");
  add_json_flag(*command, options->json);
  command->callback([options] { run_meshes(*options); });
}

}  // namespace clothcd::cli
