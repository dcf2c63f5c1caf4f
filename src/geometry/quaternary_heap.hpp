#pragma once
// Private: a 4-ary min-heap of small entries. The tree is half as deep as a binary heap and the four children of a node
// are adjacent (64 bytes for 16-byte entries), so a pop from a large heap touches about half as many cache lines.

#include <cstddef>
#include <utility>
#include <vector>

namespace clothcd::geometry::detail {

/// Min-heap on `Entry::cost` (any type with a `cost` member ordered by `<`), four children per node. Ties pop in an
/// unspecified order.
template <typename Entry>
class QuaternaryHeap {
 public:
  /// Reserves room for `count` entries.
  void reserve(std::size_t count) { entries_.reserve(count); }
  /// True when no entry is left.
  [[nodiscard]] bool empty() const { return entries_.empty(); }
  /// Number of entries.
  [[nodiscard]] std::size_t size() const { return entries_.size(); }

  /// Adds an entry without restoring the heap order; call heapify() before the next push() or pop().
  void push_unordered(const Entry& e) { entries_.push_back(e); }

  /// Restores the heap order over every entry (O(n)).
  void heapify() {
    if (entries_.size() < 2) return;
    for (std::size_t i = (entries_.size() - 2) / 4 + 1; i-- > 0;) sift_down(i);
  }

  /// Drops every entry for which `keep(entry)` is false and restores the heap order (O(n)).
  template <typename Keep>
  void retain_if(Keep keep) {
    std::size_t kept = 0;
    for (const Entry& e : entries_)
      if (keep(e)) entries_[kept++] = e;
    entries_.resize(kept);
    heapify();
  }

  /// Adds an entry.
  void push(const Entry& e) {
    entries_.push_back(e);
    std::size_t i = entries_.size() - 1;
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!(e.cost < entries_[parent].cost)) break;
      entries_[i] = entries_[parent];
      i = parent;
    }
    entries_[i] = e;
  }

  /// Removes and returns the entry of least cost. The heap must not be empty.
  Entry pop() {
    const Entry top = entries_.front();
    entries_.front() = entries_.back();
    entries_.pop_back();
    if (!entries_.empty()) sift_down(0);
    return top;
  }

 private:
  void sift_down(std::size_t i) {
    const Entry e = entries_[i];
    const std::size_t n = entries_.size();
    for (;;) {
      const std::size_t first = 4 * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t last = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < last; ++c)
        if (entries_[c].cost < entries_[best].cost) best = c;
      if (!(entries_[best].cost < e.cost)) break;
      entries_[i] = entries_[best];
      i = best;
    }
    entries_[i] = e;
  }

  std::vector<Entry> entries_;
};

}  // namespace clothcd::geometry::detail
