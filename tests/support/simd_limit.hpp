#pragma once
// Runs a test's code at one SIMD level: caps clothcd::simd_level() for the lifetime of the object.

#include "support/simd_level.hpp"

namespace clothcd::test {

/// Caps the process's SIMD level at `limit` until destroyed, then lifts the cap.
class SimdLimit {
 public:
  explicit SimdLimit(SimdLevel limit) { set_simd_level_limit(limit); }
  ~SimdLimit() { set_simd_level_limit(SimdLevel::Avx512); }
  SimdLimit(const SimdLimit&) = delete;
  SimdLimit& operator=(const SimdLimit&) = delete;
};

}  // namespace clothcd::test
