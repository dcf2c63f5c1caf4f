#pragma once
// An in-place most-significant-digit radix sort of (key, index) pairs (American flag sort: McIlroy, Bostic and
// McIlroy, "Engineering radix sort", 1993): linear time for the detector's canonical output order, where a comparison
// sort of thousands of collisions per call cost more than their narrow phase, and no second array, so that the sort
// of millions of collisions needs no memory beyond the pairs themselves.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace clothcd::detail {

/// A 64-bit sort key and the position it belongs to.
struct KeyedIndex {
  std::uint64_t key = 0;    ///< Sort key.
  std::uint64_t index = 0;  ///< Payload (a position in the detector's output).
};

namespace radix_sort_passes {

// Below this many items, an insertion sort is cheaper than another digit's counts.
inline constexpr std::ptrdiff_t kInsertionSortItems = 32;

inline void insertion_sort(KeyedIndex* first, KeyedIndex* last) {
  for (KeyedIndex* i = first + 1; i < last; ++i) {
    const KeyedIndex item = *i;
    KeyedIndex* j = i;
    for (; j > first && (j - 1)->key > item.key; --j) *j = *(j - 1);
    *j = item;
  }
}

// Sorts [first, last), whose keys agree above bit shift + 8, by the 8-bit digit at `shift`, then each digit's range by
// the lower digits.
inline void sort_digit(KeyedIndex* first, KeyedIndex* last, int shift) {
  if (last - first <= kInsertionSortItems) {
    insertion_sort(first, last);
    return;
  }
  const auto digit = [shift](const KeyedIndex& item) { return static_cast<std::size_t>((item.key >> shift) & 0xff); };
  std::array<std::size_t, 257> start{};
  for (const KeyedIndex* p = first; p < last; ++p) ++start[digit(*p) + 1];
  for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
  // Each item is swapped straight into the next free slot of its digit's range until the slot at hand holds an item of
  // the range being filled.
  std::array<std::size_t, 256> next{};
  for (std::size_t d = 0; d < next.size(); ++d) next[d] = start[d];
  for (std::size_t d = 0; d < next.size(); ++d) {
    while (next[d] < start[d + 1]) {
      KeyedIndex item = first[next[d]];
      for (std::size_t home = digit(item); home != d; home = digit(item)) std::swap(item, first[next[home]++]);
      first[next[d]++] = item;
    }
  }
  if (shift == 0) return;
  for (std::size_t d = 0; d < next.size(); ++d) {
    if (start[d + 1] - start[d] > 1) sort_digit(first + start[d], first + start[d + 1], shift - 8);
  }
}

}  // namespace radix_sort_passes

/// Sorts `items` by key in place (not stably: equal keys may end in any order), with 8-bit digits from the highest one
/// the largest key uses.
inline void radix_sort_by_key(std::vector<KeyedIndex>& items) {
  std::uint64_t largest = 0;
  for (const KeyedIndex& item : items) largest = item.key > largest ? item.key : largest;
  int shift = 0;
  while (shift < 56 && (largest >> (shift + 8)) != 0) shift += 8;
  radix_sort_passes::sort_digit(items.data(), items.data() + items.size(), shift);
}

}  // namespace clothcd::detail
