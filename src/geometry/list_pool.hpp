#pragma once
// Private: many short lists of ints (the faces or candidate pairs at each vertex of QEM simplification) in one array.
// One allocation instead of one per list, and lists of vertices numbered close together lie close together in memory.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace clothcd::geometry::detail {

/// Lists 0 .. n-1 of ints in one array. Each list has a block of room; a list outgrowing its block moves to a new
/// block, twice as large, at the end of the array (its old block is not reused). Any growth may move every list:
/// pointers from begin()/end() and views stay valid only until the next push_back() or reserve().
class ListPool {
 public:
  /// Empty lists with room for `room[i]` entries in list i, laid out in list order.
  void reset(const std::vector<int>& room) {
    blocks_.resize(room.size());
    std::size_t total = 0;
    for (std::size_t i = 0; i < room.size(); ++i) {
      blocks_[i] = {std::uint32_t(total), 0, std::uint32_t(room[i])};
      total += std::size_t(room[i]);
    }
    // Room for moved lists up front: growing the vector would copy every list and touch twice the memory.
    data_.reserve(2 * total);
    data_.assign(total, 0);
  }

  /// The entries of list i, for range-for.
  struct View {
    const int* first;
    const int* last;
    [[nodiscard]] const int* begin() const { return first; }
    [[nodiscard]] const int* end() const { return last; }
  };
  /// The entries of list i.
  [[nodiscard]] View operator[](int i) const { return {begin(i), end(i)}; }
  /// Number of entries of list i.
  [[nodiscard]] int size(int i) const { return int(blocks_[std::size_t(i)].size); }
  /// True when list i has no entry.
  [[nodiscard]] bool empty(int i) const { return blocks_[std::size_t(i)].size == 0; }
  /// First entry of list i.
  [[nodiscard]] int* begin(int i) { return data_.data() + blocks_[std::size_t(i)].begin; }
  /// Past the last entry of list i.
  [[nodiscard]] int* end(int i) { return begin(i) + blocks_[std::size_t(i)].size; }
  /// First entry of list i.
  [[nodiscard]] const int* begin(int i) const { return data_.data() + blocks_[std::size_t(i)].begin; }
  /// Past the last entry of list i.
  [[nodiscard]] const int* end(int i) const { return begin(i) + blocks_[std::size_t(i)].size; }

  /// Starts loading where list i lies (a hint; nothing changes).
  void prefetch_place(int i) const { __builtin_prefetch(&blocks_[std::size_t(i)]); }
  /// Starts loading the first entries of list i (a hint; nothing changes).
  void prefetch_entries(int i) const { __builtin_prefetch(begin(i)); }

  /// Makes room for `count` entries in list i (moving it when its block is too small).
  void reserve(int i, int count) {
    Block& b = blocks_[std::size_t(i)];
    if (std::uint32_t(count) <= b.capacity) return;
    const std::uint32_t capacity = std::max(std::uint32_t(count), 2 * b.capacity);
    const std::size_t start = data_.size();
    data_.resize(start + capacity);
    std::copy_n(data_.begin() + b.begin, b.size, data_.begin() + std::ptrdiff_t(start));
    b.begin = std::uint32_t(start);
    b.capacity = capacity;
  }

  /// Appends `x` to list i.
  void push_back(int i, int x) {
    reserve(i, size(i) + 1);
    Block& b = blocks_[std::size_t(i)];
    data_[b.begin + b.size++] = x;
  }

  /// Removes one entry equal to `x` from list i, which must hold it; the last entry takes its place.
  void remove(int i, int x) {
    Block& b = blocks_[std::size_t(i)];
    int* first = data_.data() + b.begin;
    *std::find(first, first + b.size, x) = first[b.size - 1];
    --b.size;
  }

  /// Keeps the entries x of list i for which `keep(x)` is true, in their order.
  template <typename Keep>
  void retain_if(int i, Keep keep) {
    Block& b = blocks_[std::size_t(i)];
    int* first = data_.data() + b.begin;
    // Every entry is copied and only kept ones advance the end: no branch on `keep`, which may be unpredictable.
    std::uint32_t kept = 0;
    for (std::uint32_t k = 0; k < b.size; ++k) {
      const int x = first[k];
      first[kept] = x;
      kept += std::uint32_t(bool(keep(x)));
    }
    b.size = kept;
  }

  /// Empties list i (its block stays its own).
  void clear(int i) { blocks_[std::size_t(i)].size = 0; }

 private:
  struct Block {
    std::uint32_t begin, size, capacity;
  };
  std::vector<Block> blocks_;
  std::vector<int> data_;
};

}  // namespace clothcd::geometry::detail
