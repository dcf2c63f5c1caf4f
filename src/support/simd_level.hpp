#pragma once
/// @file
/// The one run-time switch of clothcd's wide (SIMD) code paths. The library is compiled for the target's baseline;
/// its wide kernels are also compiled for AVX2 and AVX-512 on x86-64 (GCC or Clang), and the widest level the CPU
/// runs is chosen at run time. Every level gives the same results, bit for bit, except the sums named where they are
/// made (a wide sum may add in another order).

#include <vector>

namespace clothcd {

/// The instruction sets the wide kernels are compiled for, narrowest first.
enum class SimdLevel {
  Baseline,  ///< The target's baseline (SSE2 on x86-64, NEON on 64-bit ARM, plain scalar code elsewhere).
  Avx2,      ///< x86-64 with AVX2 and BMI2: eight floats or four doubles per instruction.
  Avx512,    ///< x86-64 with AVX2, BMI2 and AVX-512F: eight doubles per instruction.
};

/// The widest level this CPU runs and the library is compiled for (ignores set_simd_level_limit).
[[nodiscard]] SimdLevel cpu_simd_level();

/// The level the wide kernels run at: the narrower of cpu_simd_level() and the limit of set_simd_level_limit.
[[nodiscard]] SimdLevel simd_level();

/// Every level this CPU runs, Baseline first and cpu_simd_level() last: what a test compares against the baseline.
[[nodiscard]] std::vector<SimdLevel> cpu_simd_levels();

/// Caps the level of the whole process at `limit` (the default, SimdLevel::Avx512, caps nothing): Baseline runs the
/// baseline code everywhere. For tests that compare the levels on one machine, and for checking a result on the
/// baseline. Call it while no other clothcd call runs; objects built before (geometry::SupportPoints) keep the level
/// they were built with.
void set_simd_level_limit(SimdLevel limit);

/// The level's name: "baseline", "avx2" or "avx512".
[[nodiscard]] const char* simd_level_name(SimdLevel level);

}  // namespace clothcd
