#pragma once
// Private: the run-time CPU check of the geometry code paths compiled for AVX2.

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// Defined when the AVX2 paths are compiled in (functions marked __attribute__((target("avx2")))).
#define CLOTHCD_GEOMETRY_AVX2 1
#endif

namespace clothcd::geometry::detail {

/// Whether this CPU runs the AVX2 paths (false where they are not compiled in).
[[nodiscard]] bool avx2_available();

}  // namespace clothcd::geometry::detail
