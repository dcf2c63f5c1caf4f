#pragma once
// The one place where a search's overlap tests take its gap bound (TraversalSettings::gap_bound; internal to the broad
// phase): the descent's node volume tests, the leaf pairs' primitive tests, the moved-vertex queries and the
// brute-force reference all test through these functions. A search without a bound tests with NoGap, which is the
// plain overlap test of the volumes; a bounded one with the bound's value, read at each test: two volumes then pass
// when their gap along every axis is at most that value.
// The box test compares the rounded per-axis differences with the bound: rounding is monotone, so a difference that is
// at most the bound stays so once rounded, the test is symmetric in its two boxes, and with a bound of 0 it is exactly
// the overlap test. The other volumes take the first volume grown outwards (reach_box, a sphere's radius), loosely
// enough that it overlaps every box that passes the box test against it, so that the node tests, the packed
// pre-selection and the OBB test never drop a pair that the final box test would pass.

#include <atomic>
#include <cmath>

#include "broadphase/packed_boxes.hpp"
#include "broadphase/swept_boxes.hpp"
#include "clothcd/geometry/bounding_volumes.hpp"
#include "geometry/box_obb_overlap.hpp"

namespace clothcd::broadphase::detail {

/// The gap of a search without a bound: its tests are the plain overlap tests.
struct NoGap {};

/// How a search without a gap bound reads it: always NoGap (so its tests compile to the plain overlap tests).
struct Touching {
  /// Searches of this kind order nothing by distance.
  static constexpr bool kBounded = false;
  /// The gap of the next test.
  [[nodiscard]] NoGap gap() const { return {}; }
};

/// How a search with a gap bound reads it: its current value at each test.
struct WithinBound {
  /// Searches of this kind visit near node pairs first (see traversal.cpp).
  static constexpr bool kBounded = true;
  const std::atomic<double>* bound;  ///< TraversalSettings::gap_bound (>= 0, only lowered during a search).
  /// The gap of the next test: the bound's value now.
  [[nodiscard]] double gap() const { return bound->load(std::memory_order_relaxed); }
};

/// True when the closed boxes overlap.
[[nodiscard]] inline bool within(const FlatBox& a, const FlatBox& b, NoGap) { return a.overlaps(b); }

/// True when the boxes are within `gap` (>= 0) of each other along every axis: each of the six per-axis differences,
/// rounded, is at most `gap` (a gap of 0: exactly FlatBox::overlaps; +infinity: any two boxes). Symmetric in a and b,
/// and monotone: a box that contains `a` passes with `b` whenever `a` does.
[[nodiscard]] inline bool within(const FlatBox& a, const FlatBox& b, double gap) {
  return (a.min[0] - b.max[0] <= gap) & (b.min[0] - a.max[0] <= gap) & (a.min[1] - b.max[1] <= gap) &
         (b.min[1] - a.max[1] <= gap) & (a.min[2] - b.max[2] <= gap) & (b.min[2] - a.max[2] <= gap);
}

/// `box` grown by a little more than `gap` (>= 0) on every side, rounded outwards: it overlaps every box that is
/// within(box, other, gap), and so does every volume that contains that box. A gap of 0 returns `box` itself.
[[nodiscard]] inline FlatBox reach_box(const FlatBox& box, double gap) {
  if (gap == 0.0) return box;
  // `within` passes a difference that rounds down to the gap, up to half a unit in its last place above it: the
  // 2^-50 covers that (and the subnormal step, a gap that small), the final step the rounding of each sum.
  const double grow = gap + (gap * 0x1p-50 + 0x1p-1074);
  FlatBox out;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min[k] - grow, hi = box.max[k] + grow;
    out.min[k] = lo - (std::fabs(lo) * 0x1p-52 + 0x1p-1074);
    out.max[k] = hi + (std::fabs(hi) * 0x1p-52 + 0x1p-1074);
  }
  return out;
}

/// The packed query of a box whose packed copy is `packed`, without a gap: `packed` itself.
[[nodiscard]] inline PackedBox packed_reach(const FlatBox&, const PackedBox& packed, NoGap) { return packed; }

/// The packed query of `box` within `gap`: the packed copy of reach_box(box, gap), which a packed box passes whenever
/// the box it was made from is within `gap` of `box`.
[[nodiscard]] inline PackedBox packed_reach(const FlatBox& box, const PackedBox&, double gap) {
  return pack_box(reach_box(box, gap));
}

/// True when the closed spheres share a point.
[[nodiscard]] inline bool within(const geometry::Sphere& a, const geometry::Sphere& b, NoGap) { return a.overlaps(b); }

/// True when the spheres may hold points within `gap` (>= 0) of each other along every axis: `a` with its radius
/// grown by sqrt(3) times the gap (points that close are at most that far apart), rounded up, overlaps `b`.
[[nodiscard]] inline bool within(const geometry::Sphere& a, const geometry::Sphere& b, double gap) {
  if (gap == 0.0 || a.radius < 0.0) return a.overlaps(b);
  // Above sqrt(3) by 2^-48 of it, for a difference that rounds to the gap and for the sum's rounding.
  constexpr double kSqrt3Up = 1.7320508075688834;
  geometry::Sphere grown = a;
  grown.radius = (a.radius + gap * kSqrt3Up) * (1.0 + 0x1p-50);
  return grown.overlaps(b);
}

/// True unless a separating axis parts `box` from `obb` (geometry::box_obb_overlap).
[[nodiscard]] inline bool within(const FlatBox& box, const geometry::Obb& obb, NoGap) {
  return geometry::box_obb_overlap(box.min, box.max, obb);
}

/// True unless a separating axis parts reach_box(box, gap) from `obb`: the OBB may hold points within `gap` of the box
/// along every axis.
[[nodiscard]] inline bool within(const FlatBox& box, const geometry::Obb& obb, double gap) {
  const FlatBox reach = reach_box(box, gap);
  return geometry::box_obb_overlap(reach.min, reach.max, obb);
}

}  // namespace clothcd::broadphase::detail
