// The run-time CPU check of the AVX2 code paths, done once.
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

}  // namespace clothcd
