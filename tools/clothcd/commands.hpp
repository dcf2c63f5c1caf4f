#pragma once
// Subcommand registration for the clothcd program: each command_*.cpp adds one subcommand to the app.

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace clothcd::cli {

/// A check that an option's text is a finite number from `low` (excluded when `low_open`) up to `high` (no bound when
/// infinite): NaN and infinities are refused, which CLI::Range lets through or prints as 309-digit bounds.
inline CLI::Validator finite_number(double low, double high, bool low_open = false) {
  std::ostringstream range;
  if (std::isfinite(high)) {
    range << "must be a finite number " << (low_open ? "above " : "from ") << low << (low_open ? " and at most " : " to ")
          << high;
  } else {
    range << "must be a finite number " << (low_open ? "> " : ">= ") << low;
  }
  return CLI::Validator(
      [low, high, low_open, message = range.str()](std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool ok = !text.empty() && end == text.c_str() + text.size() && std::isfinite(value) &&
                        (low_open ? value > low : value >= low) && value <= high;
        return ok ? std::string() : message;
      },
      "NUMBER");
}

/// A check that an option's text is a whole number >= 0 below 2^64 (an unsigned option would take "-1" as 2^64 - 1).
inline const CLI::Validator kSeedNumber(
    [](std::string& text) {
      const bool digits = !text.empty() && text.size() <= 20 && text.find_first_not_of("0123456789") == std::string::npos;
      return digits && (text.size() < 20 || text <= "18446744073709551615") ? std::string()
                                                                          : "must be a whole number from 0 to 2^64 - 1";
    },
    "SEED");

/// `value` as a stream prints it by default when `defined`, else `undefined` (a measure without the data it needs).
inline std::string measure_text(bool defined, double value, const char* undefined) {
  if (!defined) return undefined;
  std::ostringstream text;
  text << value;
  return text.str();
}

/// "a,b,c" split at its commas ("" gives one empty item).
inline std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::size_t begin = 0;
  for (std::size_t comma = text.find(','); comma != std::string::npos; comma = text.find(',', begin)) {
    items.push_back(text.substr(begin, comma - begin));
    begin = comma + 1;
  }
  items.push_back(text.substr(begin));
  return items;
}

/// A check that a comma-separated list has no empty item ("box,,box", a trailing comma), which CLI11's own splitting
/// would drop silently; with `seeds`, every item must also pass kSeedNumber.
inline CLI::Validator comma_list(bool seeds = false) {
  return CLI::Validator(
      [seeds](std::string& text) {
        for (std::string item : split_commas(text)) {
          if (item.empty()) return std::string("empty item in the comma-separated list '") + text + "'";
          if (seeds && !kSeedNumber(item).empty()) return "'" + item + "' " + kSeedNumber(item);
        }
        return std::string();
      },
      seeds ? "SEED,..." : "NAME,...");
}

/// Adds `clothcd info MESH`.
void add_info_command(CLI::App& app);
/// Adds `clothcd convert IN OUT`.
void add_convert_command(CLI::App& app);
/// Adds `clothcd meshes [--cache DIR]`.
void add_meshes_command(CLI::App& app);
/// Adds `clothcd detect T0_MESH T1_MESH [--thickness H] [--bvh KIND] [--filter F] [--json] [--out FILE.json]`.
void add_detect_command(CLI::App& app);
/// Adds `clothcd proximity MESH --distance D [--minimum] [--contacts] [--bvh KIND] [--json] [--out FILE.json]`.
void add_proximity_command(CLI::App& app);
/// Adds `clothcd intersections MESH [--free] [--bvh KIND] [--json] [--out FILE.json]`.
void add_intersections_command(CLI::App& app);
/// Adds `clothcd ccd PATH [--type vf|ee] [--filter ...] [--thickness H] [--json] [--per-query FILE]`.
void add_ccd_command(CLI::App& app);
/// Adds `clothcd simplify IN OUT (--ratio R | --faces N) [--non-edge-threshold D] [--hausdorff]`.
void add_simplify_command(CLI::App& app);
/// Adds `clothcd obb MESH [--method ...] [--simplify R] [--json]`.
void add_obb_command(CLI::App& app);
/// Adds `clothcd train DATASET --out DIR`.
void add_train_command(CLI::App& app);
/// Adds `clothcd evaluate MODEL DATASET`.
void add_evaluate_command(CLI::App& app);
/// Adds `clothcd simulate --scene NAME --cloth A|B|C [--steps N] [--dt S] [--filter ...] [--bvh ...] --out DIR`.
void add_simulate_command(CLI::App& app);
/// Adds `clothcd gen-dataset --out FILE.csv [--scenes ...] [--cloths ...] [--steps N] [--seeds ...] [--max-rows N]`.
void add_gen_dataset_command(CLI::App& app);
/// Adds `clothcd bench all|NAME --out DIR [--quick] [...]`: forwards to the clothcd-bench program.
void add_bench_command(CLI::App& app);

}  // namespace clothcd::cli
