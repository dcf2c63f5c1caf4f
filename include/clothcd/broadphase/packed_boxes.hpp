#pragma once
/// @file
/// Primitive data in structure-of-arrays layout for testing one primitive against four or eight at a time:
/// single-precision copies of swept boxes rounded outwards, and the primitives' vertex indices. The box copies only
/// pre-select: a pair they pass is confirmed on the double-precision boxes, so results are those of the FlatBox tests
/// exactly. The four-lane operations use the compiler's vector extension (SSE on x86-64, NEON on ARM); the eight-lane
/// ones (x86-64 with GCC or Clang) are compiled for AVX2 and may only run where avx2_supported() is true.

#include <cstring>
#include <vector>

#include "clothcd/broadphase/swept_boxes.hpp"
#include "clothcd/cpu_features.hpp"

#if !defined(CLOTHCD_AVX2_PATHS) && defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace clothcd::broadphase {

/// Entries after the last primitive in every packed row (so that eight consecutive entries can be read from any valid
/// position); padding boxes are empty and padding vertex indices are -1.
inline constexpr int kPackedPadding = 7;

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
[[nodiscard]] inline Vector load_lanes(const Value* p) {
  static_assert(sizeof(Vector) == 4 * sizeof(Value), "four lanes");
  Vector v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

#if defined(CLOTHCD_AVX2_PATHS)
/// Eight consecutive values from `p` (any alignment) as one vector `Vector`. AVX2 only.
template <class Vector, class Value>
[[nodiscard]] CLOTHCD_AVX2 inline Vector load_eight_lanes(const Value* p) {
  static_assert(sizeof(Vector) == 8 * sizeof(Value), "eight lanes");
  Vector v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
#endif
}  // namespace packed_detail

/// One box in single precision, each bound rounded outwards (it contains the FlatBox it was made from).
struct PackedBox {
  float lo[3];  ///< Lower corner, rounded down.
  float hi[3];  ///< Upper corner, rounded up.
};

/// The outward-rounded single-precision copy of `box` (bounds not NaN; infinite or beyond the float range is fine).
[[nodiscard]] PackedBox pack_box(const FlatBox& box);

/// Boxes stored as six rows of floats (lo x, y, z, hi x, y, z), each padded by kPackedPadding never-overlapping
/// entries.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class PackedBoxes {
 public:
  /// Replaces the contents with outward-rounded copies of `boxes`.
  void assign(const std::vector<FlatBox>& boxes);

  /// Replaces box j (0 <= j < size()) with an outward-rounded copy of `box`: what assign() would store for it.
  void set(int j, const FlatBox& box) {
    const PackedBox p = pack_box(box);
    for (int k = 0; k < 3; ++k) {
      rows_[static_cast<std::size_t>(k * stride_ + j)] = p.lo[k];
      rows_[static_cast<std::size_t>((3 + k) * stride_ + j)] = p.hi[k];
    }
  }

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

#if defined(CLOTHCD_AVX2_PATHS)
  /// overlap_lanes for boxes j .. j + 7, as bits (bit k for box j + k). AVX2 only.
  [[nodiscard]] CLOTHCD_AVX2 unsigned overlap_bits8(int j, const PackedBox& q) const {
    const float* r = rows_.data() + j;
    const int s = stride_;
    const auto lanes = (q.lo[0] <= load8(r + 3 * s)) & (load8(r) <= q.hi[0]) & (q.lo[1] <= load8(r + 4 * s)) &
                       (load8(r + s) <= q.hi[1]) & (q.lo[2] <= load8(r + 5 * s)) & (load8(r + 2 * s) <= q.hi[2]);
    return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(lanes)));
  }
#endif

 private:
  using Floats = float __attribute__((vector_size(16)));
  static Floats load(const float* p) { return packed_detail::load_lanes<Floats>(p); }
#if defined(CLOTHCD_AVX2_PATHS)
  using Floats8 = float __attribute__((vector_size(32)));
  CLOTHCD_AVX2 static Floats8 load8(const float* p) { return packed_detail::load_eight_lanes<Floats8>(p); }
#endif

  std::vector<float> rows_;
  int size_ = 0;
  int stride_ = 0;
};

/// The vertex indices of edges (2 rows) or faces (3 rows) as rows of ints, each padded by kPackedPadding entries of
/// -1, so that four or eight consecutive primitives can be compared with a vertex at once.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class PackedVertexIds {
 public:
  /// Replaces the contents: `ids` holds `per_primitive` (2 or 3) indices (>= 0) per primitive, one after the other.
  void assign(const std::vector<int>& ids, int per_primitive);

  /// Lane k true when edge j + k uses vertex `v` or `w` (>= 0); false at or beyond the last edge. Edge rows only.
  [[nodiscard]] LaneMask edge_uses_lanes(int j, int v, int w) const {
    const LaneMask first = load(rows_.data() + j), second = load(rows_.data() + j + stride_);
    return (first == v) | (second == v) | (first == w) | (second == w);
  }

  /// Lane k true when face j + k uses vertex `v` (>= 0); false at or beyond the last face. Face rows only.
  [[nodiscard]] LaneMask face_uses_lanes(int j, int v) const {
    const int* r = rows_.data() + j;
    return (load(r) == v) | (load(r + stride_) == v) | (load(r + 2 * stride_) == v);
  }

#if defined(CLOTHCD_AVX2_PATHS)
  /// edge_uses_lanes for edges j .. j + 7, as bits (bit k for edge j + k). AVX2 only.
  [[nodiscard]] CLOTHCD_AVX2 unsigned edge_uses_bits8(int j, int v, int w) const {
    const Ints8 first = load8(rows_.data() + j), second = load8(rows_.data() + j + stride_);
    return bits8((first == v) | (second == v) | (first == w) | (second == w));
  }

  /// face_uses_lanes for faces j .. j + 7, as bits (bit k for face j + k). AVX2 only.
  [[nodiscard]] CLOTHCD_AVX2 unsigned face_uses_bits8(int j, int v) const {
    const int* r = rows_.data() + j;
    return bits8((load8(r) == v) | (load8(r + stride_) == v) | (load8(r + 2 * stride_) == v));
  }
#endif

 private:
#if defined(CLOTHCD_AVX2_PATHS)
  using Ints8 = int __attribute__((vector_size(32)));
  CLOTHCD_AVX2 static Ints8 load8(const int* p) { return packed_detail::load_eight_lanes<Ints8>(p); }
  CLOTHCD_AVX2 static unsigned bits8(Ints8 lanes) {
    return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(lanes)));
  }
#endif

  static LaneMask load(const int* p) { return packed_detail::load_lanes<LaneMask>(p); }

  std::vector<int> rows_;
  int stride_ = 0;
};

}  // namespace clothcd::broadphase
