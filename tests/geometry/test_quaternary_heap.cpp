// The 4-ary heap of QEM simplification against a sorted multiset on seeded random push/pop/purge sequences.
#include <catch2/catch.hpp>

#include <random>
#include <set>
#include <utility>

#include "geometry/quaternary_heap.hpp"

using clothcd::geometry::detail::QuaternaryHeap;

namespace {

struct Entry {
  float cost;
  int id;
};

}  // namespace

TEST_CASE("QuaternaryHeap pops the same costs as a sorted reference", "[geometry][qem][heap]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    // Few distinct costs: many ties, as degenerate (flat) regions give.
    std::uniform_int_distribution<int> cost_of(0, seed == 3 ? 4 : 1000);
    std::uniform_int_distribution<int> action(0, 9);
    QuaternaryHeap<Entry> heap;
    std::multiset<std::pair<float, int>> reference;  // (cost, id)
    for (int i = 0; i < 200; ++i) {  // bulk start, as simplify_qem fills it
      const Entry e{float(cost_of(rng)), i};
      heap.push_unordered(e);
      reference.insert({e.cost, e.id});
    }
    heap.heapify();
    for (int step = 0; step < 5000; ++step) {
      const int a = action(rng);
      if (a < 5) {
        const Entry e{float(cost_of(rng)), 200 + step};  // ids unique
        heap.push(e);
        reference.insert({e.cost, e.id});
      } else if (a < 9 && !reference.empty()) {
        REQUIRE_FALSE(heap.empty());
        const Entry top = heap.pop();
        REQUIRE(top.cost == reference.begin()->first);  // ties may pop in any order: the entry itself must be there
        const auto it = reference.find({top.cost, top.id});
        REQUIRE(it != reference.end());
        reference.erase(it);
      } else if (a == 9) {  // purge the odd ids from both
        heap.retain_if([](const Entry& e) { return e.id % 2 == 0; });
        for (auto it = reference.begin(); it != reference.end();) it = it->second % 2 ? reference.erase(it) : ++it;
      }
      REQUIRE(heap.size() == reference.size());
    }
    while (!reference.empty()) {
      const Entry top = heap.pop();
      REQUIRE(top.cost == reference.begin()->first);
      REQUIRE(reference.count({top.cost, top.id}) == 1);
      reference.erase({top.cost, top.id});
    }
    REQUIRE(heap.empty());
  }
}
