// The shared options of the clothcd subcommands (shared_options.hpp).
#include "shared_options.hpp"

#include <iostream>
#include <map>
#include <stdexcept>

#include "clothcd/mesh/model_catalog.hpp"

namespace clothcd::cli {

void add_filter_option(CLI::App& command, std::string& filter, const std::string& old_spelling,
                       const std::map<std::string, std::string>& old_values) {
  command.add_option("--filter", filter, "Culling before the exact CCD test (network: the pair network in front of "
                                         "the combined filters, which confirm each of its drops)")
      ->check(CLI::IsMember(kFilterNames))
      ->capture_default_str();
  if (old_spelling.empty()) return;
  // CLI11 names no hidden option in its messages: the check names it.
  command.add_option(old_spelling, filter, "old spelling of --filter")
      ->transform(CLI::Transformer(old_values))
      ->check(CLI::Validator(
          [old_spelling](std::string& value) {
            const std::string problem = CLI::IsMember(kFilterNames)(value);
            return problem.empty() ? problem : old_spelling + " (now --filter): " + problem;
          },
          ""))
      ->group("");
}

CullingMode culling_named(const std::string& filter) {
  static const std::map<std::string, CullingMode> modes = {{"none", CullingMode::None},
                                                           {"nonpenetration", CullingMode::NonPenetration},
                                                           {"projection", CullingMode::Projection},
                                                           {"combined", CullingMode::Filters},
                                                           {"network", CullingMode::Network}};
  return modes.at(filter);
}

namespace {
const std::map<std::string, HierarchyKind> kHierarchies = {
    {"sphere-root-aabb", HierarchyKind::SphereRootAabb}, {"aabb", HierarchyKind::Aabb}, {"aabb-obb", HierarchyKind::AabbObb}};
}  // namespace

void add_bvh_option(CLI::App& command, std::string& bvh) {
  command.add_option("--bvh", bvh, "Bounding volume hierarchy: the paper's double box (sphere-root-aabb), plain AABB "
                                   "tree, or its AABB-OBB hybrid")
      ->check(CLI::IsMember({"sphere-root-aabb", "aabb", "aabb-obb"}))
      ->capture_default_str();
}

HierarchyKind hierarchy_named(const std::string& bvh) { return kHierarchies.at(bvh); }

void add_approximate_flag(CLI::App& command, bool& approximate, const std::string& help) {
  CLI::Option* approximate_flag = command.add_flag(
      "--approximate", approximate,
      help + ". Deciding exactly is the default: --exact, which asked for it in earlier releases, is still accepted "
             "and does nothing");
  command.add_flag("--exact", "old opt-in to the exact decisions, now the default (no effect)")
      ->group("")
      ->excludes(approximate_flag);
}

void check_approximate_needs_zero_thickness(bool approximate, double thickness) {
  if (approximate && thickness > 0.0)
    throw std::invalid_argument(
        "--approximate changes only how the touches of thickness 0 that the floating-point fast tier leaves open are reported; "
        "with a thickness the test is a distance search with a safety margin (drop --approximate or --thickness)");
}

void add_network_option(CLI::App& command, std::string& network, const std::string& old_spelling) {
  const char* help = "Pair network for --filter network: a model folder or its network.xml (default models/default)";
  command.add_option("--network", network, help);
  if (!old_spelling.empty()) command.add_option(old_spelling, network, "old spelling of --network")->group("");
}

void check_network_needs_filter(const std::string& network, const std::string& filter) {
  if (!network.empty() && filter != "network") throw std::invalid_argument("--network needs --filter network");
}

void add_cache_option(CLI::App& command, std::string& cache, const std::string& old_spelling) {
  if (cache.empty()) cache = default_model_dir().string();
  command.add_option("--cache", cache, "Obstacle model cache folder (default $CLOTHCD_CACHE, else "
                                       "$XDG_CACHE_HOME/clothcd or ~/.cache/clothcd)")
      ->capture_default_str();
  if (!old_spelling.empty()) command.add_option(old_spelling, cache, "old spelling of --cache")->group("");
}

void add_json_flag(CLI::App& command, bool& json) {
  command.add_flag("--json", json, "Print one JSON object instead of the text report (docs/json.md)");
}

void add_quiet_flag(CLI::App& command, bool& quiet) {
  command.add_flag("--quiet,-q", quiet, "No progress on stderr");
}

Json json_report(const std::string& command) { return Json{{"schema", 1}, {"command", command}}; }

void print_json(const Json& report) { std::cout << report.dump(2) << '\n'; }

Json confusion_json(const learning::ConfusionMatrix& c) {
  return {{"true_positive", c.true_positive}, {"false_negative", c.false_negative},
          {"false_positive", c.false_positive}, {"true_negative", c.true_negative}};
}

Json class_balance_json(const learning::ClassBalance& balance) {
  Json splits = Json::object();
  for (int s = 0; s < 3; ++s)
    splits[learning::split_name(static_cast<learning::Split>(s))] = {{"rows", balance.rows[s]},
                                                                     {"filter_positive", balance.filter_positive[s]},
                                                                     {"exact_positive", balance.exact_positive[s]}};
  return splits;
}

}  // namespace clothcd::cli
