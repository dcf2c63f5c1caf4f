// The detector's radix sort gives exactly a stable comparison sort's order, for small, large and repeated keys.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "detection/radix_sort.hpp"

using clothcd::detail::KeyedIndex;

TEST_CASE("radix sort by key equals a stable sort", "[detection][sort]") {
  std::mt19937_64 rng(5);
  for (const int bits : {1, 11, 12, 30, 64}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{5000}}) {
      std::vector<KeyedIndex> items(count);
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t key = bits == 64 ? rng() : rng() & ((std::uint64_t{1} << bits) - 1);
        items[i] = {key, i};
      }
      std::vector<KeyedIndex> expected = items;
      std::stable_sort(expected.begin(), expected.end(),
                       [](const KeyedIndex& a, const KeyedIndex& b) { return a.key < b.key; });
      std::vector<KeyedIndex> scratch;
      clothcd::detail::radix_sort_by_key(items, scratch);
      REQUIRE(items.size() == expected.size());
      for (std::size_t i = 0; i < count; ++i) {
        REQUIRE(items[i].key == expected[i].key);
        REQUIRE(items[i].index == expected[i].index);
      }
    }
  }
}
