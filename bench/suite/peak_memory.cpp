// Peak memory of one piece of work (see peak_memory.hpp).
#include "peak_memory.hpp"

#include <malloc.h>

#include <fstream>
#include <string>

namespace clothcd::bench {
namespace {

// A field of /proc/self/status in KiB (VmRSS, VmHWM), -1 when absent.
long status_kib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  return -1;
}

}  // namespace

std::optional<double> peak_growth_mb(const std::function<void()>& work) {
  malloc_trim(0);  // freed memory the allocator kept would hide part of the work's growth
  std::ofstream clear("/proc/self/clear_refs");
  if (!(clear << "5" << std::flush)) return std::nullopt;  // "5" resets VmHWM to the current resident set
  const long before = status_kib("VmRSS");
  work();
  const long peak = status_kib("VmHWM");
  if (before < 0 || peak < 0) return std::nullopt;
  return static_cast<double>(peak - before) / 1024.0;
}

}  // namespace clothcd::bench
