// The re-test cache (see retest_cache.hpp).
#include "retest_cache.hpp"

#include <cstring>

namespace clothcd::detail {

namespace {

// Sets moved[v] = 1 for the rows of `now` that differ bitwise from those of `before` (same shape), else 0; returns how
// many moved.
std::size_t find_moved_rows(const Vertices& before, const Vertices& now, std::vector<std::uint8_t>& moved) {
  const std::size_t rows = static_cast<std::size_t>(now.rows());
  moved.assign(rows, 0);
  std::size_t count = 0;
  for (std::size_t v = 0; v < rows; ++v) {
    moved[v] = std::memcmp(before.data() + 3 * v, now.data() + 3 * v, 3 * sizeof(double)) != 0 ? 1 : 0;
    count += moved[v];
  }
  return count;
}

}  // namespace

bool RetestCache::repeats_last_step(const Vertices& start, const Vertices& end) {
  if (!has_last_) return false;
  if (std::memcmp(start.data(), start_.data(), sizeof(double) * start.size()) != 0) return false;
  // Beyond a quarter of the vertices, the restricted search saves little over a full one.
  return find_moved_rows(end_, end, moved_) * 4 <= static_cast<std::size_t>(end.rows());
}

void RetestCache::remember(Vertices& start, Vertices& end) {
  start_.swap(start);
  end_.swap(end);
  has_last_ = true;
}

}  // namespace clothcd::detail
