// The pooled per-vertex lists of QEM simplification against one std::vector per list on seeded random operations.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "geometry/list_pool.hpp"

using clothcd::geometry::detail::ListPool;

TEST_CASE("ListPool holds the same lists as a vector of vectors", "[geometry][qem][pool]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    CAPTURE(seed);
    std::mt19937 rng(seed);
    const int lists = 40;
    std::vector<int> room(lists);
    for (int& r : room) r = int(rng() % 4);  // some lists start with no room at all
    ListPool pool;
    pool.reset(room);
    std::vector<std::vector<int>> reference(lists);
    std::uniform_int_distribution<int> list_of(0, lists - 1), value_of(0, 30), action(0, 9);
    for (int step = 0; step < 4000; ++step) {
      const int i = list_of(rng);
      auto& ref = reference[size_t(i)];
      const int a = action(rng);
      if (a < 4) {
        const int x = value_of(rng);
        pool.push_back(i, x);
        ref.push_back(x);
      } else if (a < 6 && !ref.empty()) {  // remove a value the list holds: its first copy gives way to the last entry
        const int x = ref[rng() % ref.size()];
        pool.remove(i, x);
        *std::find(ref.begin(), ref.end(), x) = ref.back();
        ref.pop_back();
      } else if (a == 6) {  // keep the even values, in order
        pool.retain_if(i, [](int x) { return x % 2 == 0; });
        ref.erase(std::remove_if(ref.begin(), ref.end(), [](int x) { return x % 2 != 0; }), ref.end());
      } else if (a == 7) {
        pool.reserve(i, pool.size(i) + value_of(rng));
      } else if (a == 8 && step % 50 == 0) {
        pool.clear(i);
        ref.clear();
      }
      // Growth may move any list: every list must still hold its values in the same order.
      for (int j = 0; j < lists; ++j) {
        REQUIRE(pool.size(j) == int(reference[size_t(j)].size()));
        REQUIRE(pool.empty(j) == reference[size_t(j)].empty());
        REQUIRE(std::vector<int>(pool.begin(j), pool.end(j)) == reference[size_t(j)]);
      }
    }
    // The view walks the same entries as begin()/end().
    for (int j = 0; j < lists; ++j) {
      std::vector<int> seen;
      for (int x : pool[j]) seen.push_back(x);
      REQUIRE(seen == std::vector<int>(pool.begin(j), pool.end(j)));
    }
  }
}
