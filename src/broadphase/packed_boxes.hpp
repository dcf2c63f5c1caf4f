#pragma once
/// @file
/// Primitive data in structure-of-arrays layout for testing one primitive against four or eight at a time:
/// single-precision copies of swept boxes rounded outwards, and the primitives' vertex indices. The box copies only
/// pre-select: a pair they pass is confirmed on the double-precision boxes, so results are those of the FlatBox tests
/// exactly. The lane tests themselves are internal to the library (its vector layer; see support/simd_level.hpp).

#include <vector>

#include "broadphase/swept_boxes.hpp"

namespace clothcd::broadphase {

/// Entries after the last primitive in every packed row (so that eight consecutive entries can be read from any valid
/// position); padding boxes are empty and padding vertex indices are -1.
inline constexpr int kPackedPadding = 7;

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

  /// The six rows (lo x, y, z, hi x, y, z), each of stride() floats: box j's bound in row r is rows()[r * stride() + j].
  [[nodiscard]] const float* rows() const { return rows_.data(); }

  /// Entries per row: size() + kPackedPadding.
  [[nodiscard]] int stride() const { return stride_; }

 private:
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

  /// The rows (2 for edges, 3 for faces), each of stride() ints: vertex r of primitive j is rows()[r * stride() + j].
  [[nodiscard]] const int* rows() const { return rows_.data(); }

  /// Entries per row: the number of primitives + kPackedPadding.
  [[nodiscard]] int stride() const { return stride_; }

 private:
  std::vector<int> rows_;
  int stride_ = 0;
};

}  // namespace clothcd::broadphase
