#pragma once
// A stable least-significant-digit radix sort of (key, index) pairs: linear time for the detector's canonical output
// order, where a comparison sort of thousands of collisions per call cost more than their narrow phase.

#include <array>
#include <cstdint>
#include <vector>

namespace clothcd::detail {

/// A 64-bit sort key and the position it belongs to.
struct KeyedIndex {
  std::uint64_t key = 0;    ///< Sort key.
  std::uint64_t index = 0;  ///< Payload (a position in the detector's batch).
};

/// Sorts `items` by key, stably, with 11-bit digits and only as many passes as the largest key needs; `scratch` is
/// working storage.
inline void radix_sort_by_key(std::vector<KeyedIndex>& items, std::vector<KeyedIndex>& scratch) {
  std::uint64_t largest = 0;
  for (const KeyedIndex& item : items) largest = item.key > largest ? item.key : largest;
  scratch.resize(items.size());
  constexpr int kBits = 11;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kBits) - 1;
  for (int shift = 0; shift < 64 && (largest >> shift) != 0; shift += kBits) {
    std::array<std::size_t, (1 << kBits) + 1> start{};
    for (const KeyedIndex& item : items) ++start[((item.key >> shift) & kMask) + 1];
    for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    for (const KeyedIndex& item : items) scratch[start[(item.key >> shift) & kMask]++] = item;
    items.swap(scratch);
  }
}

}  // namespace clothcd::detail
