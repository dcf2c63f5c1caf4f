// The run-time CPU check of the wide kernels (one CPU query per process) and the limit that caps it.
#include "support/simd_level.hpp"

#include <atomic>

#include "support/simd.hpp"

namespace clothcd {
namespace {

std::atomic<SimdLevel> level_limit{SimdLevel::Avx512};

SimdLevel detect_level() {
#if defined(CLOTHCD_SIMD_X86)
  if (__builtin_cpu_supports("avx2") == 0 || __builtin_cpu_supports("bmi2") == 0) return SimdLevel::Baseline;
  return __builtin_cpu_supports("avx512f") != 0 ? SimdLevel::Avx512 : SimdLevel::Avx2;
#else
  return SimdLevel::Baseline;
#endif
}

}  // namespace

SimdLevel cpu_simd_level() {
  static const SimdLevel cpu = detect_level();
  return cpu;
}

SimdLevel simd_level() {
  const SimdLevel limit = level_limit.load(std::memory_order_relaxed);
  return cpu_simd_level() < limit ? cpu_simd_level() : limit;
}

std::vector<SimdLevel> cpu_simd_levels() {
  std::vector<SimdLevel> levels{SimdLevel::Baseline};
  if (cpu_simd_level() >= SimdLevel::Avx2) levels.push_back(SimdLevel::Avx2);
  if (cpu_simd_level() >= SimdLevel::Avx512) levels.push_back(SimdLevel::Avx512);
  return levels;
}

void set_simd_level_limit(SimdLevel limit) { level_limit.store(limit, std::memory_order_relaxed); }

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::Avx2:
      return "avx2";
    case SimdLevel::Avx512:
      return "avx512";
    case SimdLevel::Baseline:
      break;
  }
  return "baseline";
}

}  // namespace clothcd
