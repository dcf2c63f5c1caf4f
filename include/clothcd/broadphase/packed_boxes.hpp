#pragma once
/// @file
/// Primitive data in structure-of-arrays layout for testing one primitive against four at a time: single-precision
/// copies of swept boxes rounded outwards, and the primitives' vertex indices. The box copies only pre-select: a pair
/// they pass is confirmed on the double-precision boxes, so results are those of the FlatBox tests exactly.
/// The four-lane operations use the compiler's vector extension (SSE on x86-64, NEON on ARM).

#include <cstring>
#include <vector>

#include "clothcd/broadphase/swept_boxes.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace clothcd::broadphase {

/// Four 32-bit lanes, each all ones (true) or zero (false): the result of a four-at-a-time test.
using LaneMask = int __attribute__((vector_size(16)));

/// Bit k set when lane k of `lanes` is true.
[[nodiscard]] inline unsigned lane_bits(LaneMask lanes) {
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(reinterpret_cast<__m128i>(lanes))));
#else
  return static_cast<unsigned>((lanes[0] & 1) | (lanes[1] & 2) | (lanes[2] & 4) | (lanes[3] & 8));
#endif
}

namespace packed_detail {
/// Four consecutive values from `p` (any alignment) as one vector `Vector`.
template <class Vector, class Value>
[[nodiscard]] inline Vector load4(const Value* p) {
  static_assert(sizeof(Vector) == 4 * sizeof(Value), "four lanes");
  Vector v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
}  // namespace packed_detail

/// One box in single precision, each bound rounded outwards (it contains the FlatBox it was made from).
struct PackedBox {
  float lo[3];  ///< Lower corner, rounded down.
  float hi[3];  ///< Upper corner, rounded up.
};

/// The outward-rounded single-precision copy of `box` (bounds not NaN; infinite or beyond the float range is fine).
[[nodiscard]] PackedBox pack_box(const FlatBox& box);

/// Boxes stored as six rows of floats (lo x, y, z, hi x, y, z), each padded by three never-overlapping entries so that
/// four consecutive boxes can be read from any valid position.
class PackedBoxes {
 public:
  /// Replaces the contents with outward-rounded copies of `boxes`.
  void assign(const std::vector<FlatBox>& boxes);

  /// Number of boxes.
  [[nodiscard]] int size() const { return size_; }

  /// Box j as a PackedBox (0 <= j < size()).
  [[nodiscard]] PackedBox at(int j) const {
    const float* r = rows_.data() + j;
    const int s = stride_;
    return PackedBox{{r[0], r[s], r[2 * s]}, {r[3 * s], r[4 * s], r[5 * s]}};
  }

  /// Lane k true when box j + k may overlap `q`: true whenever the original boxes overlap (never a false
  /// "separated"); false at or beyond size(). Requires 0 <= j < size().
  [[nodiscard]] LaneMask overlap_lanes(int j, const PackedBox& q) const {
    const float* r = rows_.data() + j;
    const int s = stride_;
    return (q.lo[0] <= load(r + 3 * s)) & (load(r) <= q.hi[0]) & (q.lo[1] <= load(r + 4 * s)) &
           (load(r + s) <= q.hi[1]) & (q.lo[2] <= load(r + 5 * s)) & (load(r + 2 * s) <= q.hi[2]);
  }

 private:
  using Floats = float __attribute__((vector_size(16)));
  static Floats load(const float* p) { return packed_detail::load4<Floats>(p); }

  std::vector<float> rows_;
  int size_ = 0;
  int stride_ = 0;
};

/// The vertex indices of edges (2 rows) or faces (3 rows) as rows of ints, each padded by three entries of -1, so
/// that four consecutive primitives can be compared with a vertex at once.
class PackedVertexIds {
 public:
  /// Replaces the contents: `ids` holds `per_primitive` (2 or 3) indices (>= 0) per primitive, one after the other.
  void assign(const std::vector<int>& ids, int per_primitive);

  /// Lane k true when edge j + k uses vertex `v` (>= 0); false at or beyond the last edge. Edge rows only.
  [[nodiscard]] LaneMask edge_uses_lanes(int j, int v) const {
    const int* r = rows_.data() + j;
    return (load(r) == v) | (load(r + stride_) == v);
  }

  /// Lane k true when face j + k uses vertex `v` (>= 0); false at or beyond the last face. Face rows only.
  [[nodiscard]] LaneMask face_uses_lanes(int j, int v) const {
    const int* r = rows_.data() + j;
    return (load(r) == v) | (load(r + stride_) == v) | (load(r + 2 * stride_) == v);
  }

 private:
  static LaneMask load(const int* p) { return packed_detail::load4<LaneMask>(p); }

  std::vector<int> rows_;
  int stride_ = 0;
};

}  // namespace clothcd::broadphase
