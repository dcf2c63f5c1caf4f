#pragma once
// The options every subcommand spells the same way: --filter, --network, --cache, --json, --quiet, and the JSON
// report each command prints with --json (docs/json.md).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "clothcd/broadphase/hierarchy_kind.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/learning/classification_metrics.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::cli {

/// A JSON object whose members keep the order they were added in.
using Json = nlohmann::ordered_json;

/// The culling choices of --filter, in the order the help lists them; "combined" is the default everywhere.
inline const std::vector<std::string> kFilterNames{"none", "nonpenetration", "projection", "combined", "network"};

/// Adds `--filter NAME` (one of kFilterNames, default combined) writing into `filter`, which the caller initialises
/// to "combined". `old_spelling` (e.g. "--culling"), when given, is a hidden alias that also takes `old_values`
/// (old name -> current name).
void add_filter_option(CLI::App& command, std::string& filter, const std::string& old_spelling = "",
                       const std::map<std::string, std::string>& old_values = {});

/// The detector's culling mode of a --filter name (one of kFilterNames).
[[nodiscard]] CullingMode culling_named(const std::string& filter);

/// Adds `--bvh KIND` (sphere-root-aabb, aabb or aabb-obb; the caller initialises `bvh` to its default).
void add_bvh_option(CLI::App& command, std::string& bvh);

/// The hierarchy of a --bvh name.
[[nodiscard]] HierarchyKind hierarchy_named(const std::string& bvh);

/// Adds `--approximate` (help text `help`, to which the note on --exact is added) writing into `approximate`, and the
/// hidden `--exact` of earlier releases, which asked for what is now the default: accepted as a no-op for one release,
/// and refused together with --approximate.
void add_approximate_flag(CLI::App& command, bool& approximate, const std::string& help);

/// Throws std::invalid_argument, saying why, when --approximate comes with a thickness above 0.
void check_approximate_needs_zero_thickness(bool approximate, double thickness);

/// Adds `--network DIR` (a pair-network model folder or its network.xml, used with --filter network; default the
/// committed models/default); `old_spelling`, when given, is a hidden alias.
void add_network_option(CLI::App& command, std::string& network, const std::string& old_spelling = "");

/// Throws std::invalid_argument when a --network was given without --filter network.
void check_network_needs_filter(const std::string& network, const std::string& filter);

/// Adds `--cache DIR` (the obstacle model cache, default default_model_dir()); `old_spelling`, when given, is a
/// hidden alias.
void add_cache_option(CLI::App& command, std::string& cache, const std::string& old_spelling = "");

/// Adds `--json`: print one JSON object (docs/json.md) instead of the text report.
void add_json_flag(CLI::App& command, bool& json);

/// Adds `--quiet`: no progress on stderr.
void add_quiet_flag(CLI::App& command, bool& quiet);

/// The start of a command's JSON report: {"schema": 1, "command": NAME}.
[[nodiscard]] Json json_report(const std::string& command);

/// Prints `report` on stdout, indented, with a final newline.
void print_json(const Json& report);

/// A confusion matrix as JSON: its four counts.
[[nodiscard]] Json confusion_json(const learning::ConfusionMatrix& c);

/// Rows and labels of each split, as JSON: {"training": {"rows", "filter_positive", "exact_positive"}, ...}.
[[nodiscard]] Json class_balance_json(const learning::ClassBalance& balance);

/// A 3-vector as a JSON array.
template <typename Vector>
[[nodiscard]] Json json_vector(const Vector& v) {
  return Json::array({v[0], v[1], v[2]});
}

}  // namespace clothcd::cli
