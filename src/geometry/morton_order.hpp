#pragma once
// Private: orders points along a Morton (Z-order) curve, so points close in space get close indices. QEM
// simplification renumbers its vertices this way: the input's numbering can scatter a vertex's neighbours over the
// whole mesh, and every per-vertex array lookup then misses the cache.

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace clothcd::geometry::detail {

/// Spreads the low 10 bits of `x` so that bit i lands on bit 3 i.
inline std::uint32_t spread_bits_by_3(std::uint32_t x) {
  x &= 0x3ffu;
  x = (x | (x << 16)) & 0x030000ffu;
  x = (x | (x << 8)) & 0x0300f00fu;
  x = (x | (x << 4)) & 0x030c30c3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

/// 30-bit Morton code of a point of the unit cube (coordinates clamped to [0, 1], NaN taken as 0), 10 bits per axis,
/// x in the lowest bit of each triple.
inline std::uint32_t morton_code(const Eigen::Vector3d& p) {
  std::uint32_t code = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double t = p[axis] > 0 ? std::min(p[axis], 1.0) : 0.0;
    code |= spread_bits_by_3(static_cast<std::uint32_t>(t * 1023.0)) << axis;
  }
  return code;
}

/// Indices of `points` (unit cube) sorted by Morton code; equal codes keep their input order. A least-significant-digit
/// radix sort, three stable passes of 10 bits: no comparisons, so no mispredicted branches as in a comparison sort.
inline std::vector<int> morton_order(const std::vector<Eigen::Vector3d>& points) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> code(n), code_next(n);
  std::vector<int> order(n), order_next(n);
  for (std::size_t i = 0; i < n; ++i) {
    code[i] = morton_code(points[i]);
    order[i] = static_cast<int>(i);
  }
  constexpr int kDigitBits = 10;
  constexpr std::uint32_t kDigitMask = (1u << kDigitBits) - 1;
  std::vector<std::size_t> slot(std::size_t(1) << kDigitBits);
  for (int shift = 0; shift < 30; shift += kDigitBits) {
    std::fill(slot.begin(), slot.end(), 0);
    for (std::uint32_t c : code) ++slot[(c >> shift) & kDigitMask];
    std::size_t start = 0;
    for (std::size_t& s : slot) start += std::exchange(s, start);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t to = slot[(code[i] >> shift) & kDigitMask]++;
      code_next[to] = code[i];
      order_next[to] = order[i];
    }
    code.swap(code_next);
    order.swap(order_next);
  }
  return order;
}

}  // namespace clothcd::geometry::detail
