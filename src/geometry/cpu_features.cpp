// Run-time CPU check of the geometry code paths compiled for AVX2.
#include "cpu_features.hpp"

namespace clothcd::geometry::detail {

bool avx2_available() {
#if defined(CLOTHCD_GEOMETRY_AVX2)
  static const bool available = __builtin_cpu_supports("avx2") != 0;
  return available;
#else
  return false;
#endif
}

}  // namespace clothcd::geometry::detail
