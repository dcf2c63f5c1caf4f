#pragma once
/// @file
/// Peak memory of one piece of work in this process: the growth of the peak resident set (Linux's VmHWM, reset through
/// /proc/self/clear_refs) over the resident set before it, after the allocator has returned its free memory.

#include <functional>
#include <optional>

namespace clothcd::bench {

/// How far `work` raised the process's peak resident memory above its resident memory before it, in MiB; nothing when
/// the system cannot reset the peak (no /proc/self/clear_refs), and then `work` is not run.
[[nodiscard]] std::optional<double> peak_growth_mb(const std::function<void()>& work);

}  // namespace clothcd::bench
