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

/// Whether this CPU runs the AVX2 paths (AVX2 and BMI2 on x86-64; false where they are not compiled in).
[[nodiscard]] bool avx2_supported();

/// Whether this CPU runs the AVX-512 paths (AVX-512F on x86-64, with AVX2 and BMI2; false where they are not compiled
/// in).
[[nodiscard]] bool avx512_supported();

}  // namespace clothcd
