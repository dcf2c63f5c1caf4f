// The detector's in-place radix sort gives a comparison sort's order of keys, for small, large and repeated keys, and
// keeps every (key, index) pair.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "detection/radix_sort.hpp"

using clothcd::detail::KeyedIndex;

TEST_CASE("radix sort by key equals a comparison sort", "[detection][sort]") {
  std::mt19937_64 rng(5);
  for (const int bits : {1, 11, 12, 30, 64}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{33}, std::size_t{5000},
                                     std::size_t{100000}}) {
      std::vector<KeyedIndex> items(count);
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t key = bits == 64 ? rng() : rng() & ((std::uint64_t{1} << bits) - 1);
        items[i] = {key, i};
      }
      std::vector<KeyedIndex> expected = items;
      // Equal keys may come in any order: both sides are compared as (key, index) in order.
      const auto by_key_then_index = [](const KeyedIndex& a, const KeyedIndex& b) {
        return a.key != b.key ? a.key < b.key : a.index < b.index;
      };
      std::sort(expected.begin(), expected.end(), by_key_then_index);
      clothcd::detail::radix_sort_by_key(items);
      REQUIRE(std::is_sorted(items.begin(), items.end(),
                             [](const KeyedIndex& a, const KeyedIndex& b) { return a.key < b.key; }));
      std::sort(items.begin(), items.end(), by_key_then_index);
      REQUIRE(items.size() == expected.size());
      for (std::size_t i = 0; i < count; ++i) {
        REQUIRE(items[i].key == expected[i].key);
        REQUIRE(items[i].index == expected[i].index);
      }
    }
  }
}
