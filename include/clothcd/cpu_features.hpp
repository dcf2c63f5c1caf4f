#pragma once
/// @file
/// The run-time choice of clothcd's AVX2 (and AVX-512) code paths. The library is compiled for the x86-64 baseline; functions marked
/// CLOTHCD_AVX2 (or target("avx2")) run only where avx2_supported() is true, and give the same results as the
/// baseline code beside them.

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// Defined when the AVX2 paths are compiled in.
#define CLOTHCD_AVX2_PATHS 1
#include <immintrin.h>
/// Marks a function compiled for AVX2 and BMI2 (call it only where avx2_supported() is true).
#define CLOTHCD_AVX2 __attribute__((target("avx2,bmi2")))
#endif

namespace clothcd {

/// Whether the AVX2 paths run: the CPU has AVX2 and BMI2 (x86-64), they are compiled in, and they are enabled (see
/// set_wide_paths_enabled).
[[nodiscard]] bool avx2_supported();

/// Whether the AVX-512 paths run: avx2_supported() and the CPU has AVX-512F.
[[nodiscard]] bool avx512_supported();

/// Turns the AVX2 and AVX-512 paths off (false) or back on where the CPU has them (true, the default) for the whole
/// process. The baseline code then runs everywhere, with the same results (bit for bit, except sums that a wide path
/// adds in another order). For tests that compare the paths on one machine, and for checking a result on the baseline.
/// Call it while no other clothcd call runs; objects built while the paths were on (geometry::SupportPoints) keep them.
void set_wide_paths_enabled(bool enabled);

}  // namespace clothcd
