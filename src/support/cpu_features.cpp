// The run-time CPU checks of the AVX2 and AVX-512 code paths (each CPU query done once) and the switch that turns them
// off.
#include "clothcd/cpu_features.hpp"

#include <atomic>

namespace clothcd {
namespace {

std::atomic<bool> wide_paths_enabled{true};

}  // namespace

bool avx2_supported() {
#if defined(CLOTHCD_AVX2_PATHS)
  static const bool cpu_has = __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("bmi2") != 0;
  return cpu_has && wide_paths_enabled.load(std::memory_order_relaxed);
#else
  return false;
#endif
}

bool avx512_supported() {
#if defined(CLOTHCD_AVX2_PATHS)
  static const bool cpu_has = __builtin_cpu_supports("avx512f") != 0;
  return cpu_has && avx2_supported();
#else
  return false;
#endif
}

void set_wide_paths_enabled(bool enabled) { wide_paths_enabled.store(enabled, std::memory_order_relaxed); }

}  // namespace clothcd
