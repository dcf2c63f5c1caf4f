#pragma once
/// @file
/// Where and when a benchmark ran: the lines the report starts with.

#include <filesystem>
#include <string>

namespace clothcd::bench {

/// CPU model and logical core count from /proc/cpuinfo, e.g. "Intel(R) Xeon(R) ... (2 logical cores)"; "unknown CPU"
/// when the file is not readable.
[[nodiscard]] std::string cpu_description();

/// Operating system from /etc/os-release and the kernel release from uname, e.g. "Debian GNU/Linux 12, Linux 6.1.0".
[[nodiscard]] std::string os_description();

/// The current UTC time as "YYYY-MM-DD HH:MM UTC".
[[nodiscard]] std::string utc_now();

/// `git describe --always --dirty` of `source_dir`, or "unknown" when git or the repository is not available.
[[nodiscard]] std::string git_commit(const std::filesystem::path& source_dir);

/// The 1-minute load average from /proc/loadavg ("-" when unknown): how busy the shared machine was.
[[nodiscard]] std::string load_average();

}  // namespace clothcd::bench
