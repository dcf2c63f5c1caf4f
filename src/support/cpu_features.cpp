// The run-time CPU checks of the AVX2 and AVX-512 code paths, each done once.
#include "clothcd/cpu_features.hpp"

namespace clothcd {

bool avx2_supported() {
#if defined(CLOTHCD_AVX2_PATHS)
  static const bool supported = __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("bmi2") != 0;
  return supported;
#else
  return false;
#endif
}

bool avx512_supported() {
#if defined(CLOTHCD_AVX2_PATHS)
  static const bool supported = avx2_supported() && __builtin_cpu_supports("avx512f") != 0;
  return supported;
#else
  return false;
#endif
}

}  // namespace clothcd
