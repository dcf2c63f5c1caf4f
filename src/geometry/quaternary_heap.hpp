#pragma once
// Private: a 4-ary min-heap of small entries. The tree is half as deep as a binary heap and the four children of a node
// are adjacent (64 bytes for 16-byte entries) and start on a cache line (the storage is 64-byte aligned and the root
// sits after three unused slots), so a pop from a large heap touches about half as many cache lines.

#include <algorithm>
#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace clothcd::geometry::detail {

/// Allocator of cache-line (64-byte) aligned storage.
template <typename T>
struct CacheLineAllocator {
  using value_type = T;  ///< What is allocated.
  CacheLineAllocator() = default;
  /// Rebinding copy.
  template <typename U>
  explicit CacheLineAllocator(const CacheLineAllocator<U>& /*other*/) {}
  /// Room for n objects, 64-byte aligned.
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64))); }
  /// Frees what allocate() gave.
  void deallocate(T* p, std::size_t /*n*/) { ::operator delete(p, std::align_val_t(64)); }
  /// Any two are interchangeable.
  template <typename U>
  bool operator==(const CacheLineAllocator<U>& /*other*/) const { return true; }
  /// Any two are interchangeable.
  template <typename U>
  bool operator!=(const CacheLineAllocator<U>& /*other*/) const { return false; }
};

/// Min-heap on `Entry::cost` (any type with a `cost` member ordered by `<`), four children per node. Ties pop in an
/// unspecified order.
template <typename Entry>
class QuaternaryHeap {
 public:
  QuaternaryHeap() : entries_(kRoot) {}
  /// Reserves room for `count` entries.
  void reserve(std::size_t count) { entries_.reserve(count + kRoot); }
  /// True when no entry is left.
  [[nodiscard]] bool empty() const { return entries_.size() == kRoot; }
  /// Number of entries.
  [[nodiscard]] std::size_t size() const { return entries_.size() - kRoot; }

  /// Adds an entry without restoring the heap order; call heapify() before the next push() or pop().
  void push_unordered(const Entry& e) { entries_.push_back(e); }

  /// Restores the heap order over every entry (O(n)).
  void heapify() {
    if (size() < 2) return;
    for (std::size_t i = parent(entries_.size() - 1) + 1; i-- > kRoot;) sift_down(i);
  }

  /// Drops every entry for which `keep(entry)` is false and restores the heap order (O(n)).
  template <typename Keep>
  void retain_if(Keep keep) {
    // Every entry is copied and only the kept ones advance the end: no branch on `keep`, which is unpredictable.
    std::size_t kept = kRoot;
    for (std::size_t i = kRoot; i < entries_.size(); ++i) {
      entries_[kept] = entries_[i];
      kept += std::size_t(keep(entries_[i]));
    }
    entries_.resize(kept);
    heapify();
  }

  /// Adds an entry.
  void push(const Entry& e) {
    entries_.push_back(e);
    std::size_t i = entries_.size() - 1;
    while (i > kRoot) {
      const std::size_t up = parent(i);
      if (!(e.cost < entries_[up].cost)) break;
      entries_[i] = entries_[up];
      i = up;
    }
    entries_[i] = e;
  }

  /// The entry of least cost. The heap must not be empty.
  [[nodiscard]] const Entry& top() const { return entries_[kRoot]; }

  /// Removes and returns the entry of least cost. The heap must not be empty.
  Entry pop() {
    const Entry top = entries_[kRoot];
    entries_[kRoot] = entries_.back();
    entries_.pop_back();
    if (!empty()) sift_down(kRoot);
    return top;
  }

 private:
  // The root's slot: children of slot i are slots 4 i - 8 .. 4 i - 5, so every group of four starts at a multiple of 4.
  static constexpr std::size_t kRoot = 3;
  static constexpr std::size_t kPerLine = sizeof(Entry) < 64 ? 64 / sizeof(Entry) : 1;  // entries per cache line
  static std::size_t parent(std::size_t i) { return i / 4 + 2; }

  // The least of the four entries from `first`, by selects rather than branches: which child is least is a coin toss,
  // and mispredicted branches cost more than the comparisons.
  [[nodiscard]] std::size_t least_of_four(std::size_t first) const {
    const Entry* c = &entries_[first];
    const bool low_is_1 = c[1].cost < c[0].cost;
    const bool high_is_3 = c[3].cost < c[2].cost;
    const auto low_cost = low_is_1 ? c[1].cost : c[0].cost;
    const auto high_cost = high_is_3 ? c[3].cost : c[2].cost;
    const std::size_t low = low_is_1, high = 2 + std::size_t(high_is_3);
    // Arithmetic, as GCC turns a ?: on the indices into a branch.
    return first + low + (high - low) * std::size_t(high_cost < low_cost);
  }

  // The least of the entries first .. n - 1 (fewer than four, at least one).
  [[nodiscard]] std::size_t least_of_few(std::size_t first, std::size_t n) const {
    std::size_t best = first;
    for (std::size_t c = first + 1; c < n; ++c)
      if (entries_[c].cost < entries_[best].cost) best = c;
    return best;
  }

  void sift_down(std::size_t i) {
    const Entry e = entries_[i];
    const std::size_t n = entries_.size();
    for (;;) {
      const std::size_t first = 4 * i - 8;
      if (first >= n) break;
      // The children's children are the 16 slots from 4 first - 8: start loading them while these are compared.
      const std::size_t below = 4 * first - 8;
      const std::size_t count = below < n ? std::min<std::size_t>(16, n - below) : 0;
      for (std::size_t k = 0; k < count; k += kPerLine) __builtin_prefetch(&entries_[below + k]);
      const std::size_t best = first + 4 <= n ? least_of_four(first) : least_of_few(first, n);
      if (!(entries_[best].cost < e.cost)) break;
      entries_[i] = entries_[best];
      i = best;
    }
    entries_[i] = e;
  }

  std::vector<Entry, CacheLineAllocator<Entry>> entries_;  // slots 0 .. kRoot - 1 unused
};

}  // namespace clothcd::geometry::detail
