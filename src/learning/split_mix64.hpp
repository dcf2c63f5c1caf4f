#pragma once
// SplitMix64 (Steele, Lea and Flood): a tiny generator whose output is fixed by its definition, so that seeded
// shuffles, samples and synthetic pairs are identical on every platform (std distributions are
// implementation-defined). Private to the learning area.

#include <cstddef>
#include <cstdint>

namespace clothcd::learning {

/// Advances `state` by one step and returns the step's output.
inline unsigned long long split_mix64_next(unsigned long long& state) {
  unsigned long long z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// A SplitMix64 stream from a seed.
struct SplitMix64 {
  unsigned long long state;  ///< The seed, then the stream's position.

  /// The next 64-bit output.
  unsigned long long next() { return split_mix64_next(state); }

  /// Uniform in [0, n) by rejection, so that no value is favoured; n > 0.
  std::size_t below(std::size_t n) {
    const unsigned long long limit = UINT64_MAX - UINT64_MAX % n;
    unsigned long long r = next();
    while (r >= limit) r = next();
    return static_cast<std::size_t>(r % n);
  }

  /// Uniform in [0, 1), 53 random bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

}  // namespace clothcd::learning
