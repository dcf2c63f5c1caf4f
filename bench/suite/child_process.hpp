#pragma once
/// @file
/// Runs another program as a child process pinned to a number of CPUs and reports its exit, output and peak resident
/// memory (the kernel's own account, read with wait4), so that a measured program's memory is its own.

#include <filesystem>
#include <string>
#include <vector>

namespace clothcd::bench {

/// What a finished child process left behind.
struct ChildRun {
  int exit_code = 0;       ///< Its exit status (128 + signal when killed, 127 when it could not be started).
  std::string output;      ///< What it wrote to stdout and stderr, interleaved.
  double peak_rss_mb = 0;  ///< Its peak resident memory (ru_maxrss), in MiB.
  double wall_ms = 0;      ///< Wall time from start to exit.
};

/// Runs `arguments` (program path first) with its CPU affinity set to the first `cpus` CPUs this process may use (so
/// TBB and OpenMP size their thread pools to `cpus`), waits for it and returns what it did. Throws std::runtime_error
/// when there are fewer than `cpus` CPUs or the process cannot be created.
[[nodiscard]] ChildRun run_child(const std::vector<std::string>& arguments, int cpus);

/// The first `cpus` CPUs this process may use exist (the machine has at least that many).
[[nodiscard]] bool have_cpus(int cpus);

}  // namespace clothcd::bench
