#pragma once
// Subcommand registration for the clothcd program: each command_*.cpp adds one subcommand to the app.

#include <CLI/CLI.hpp>

namespace clothcd::cli {

/// Adds `clothcd info MESH`.
void add_info_command(CLI::App& app);
/// Adds `clothcd convert IN OUT`.
void add_convert_command(CLI::App& app);
/// Adds `clothcd meshes [--dir DIR]`.
void add_meshes_command(CLI::App& app);
/// Adds `clothcd ccd PATH [--type vf|ee] [--filter ...] [--thickness H] [--json] [--per-query FILE]`.
void add_ccd_command(CLI::App& app);

}  // namespace clothcd::cli
