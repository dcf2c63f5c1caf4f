#pragma once
// How the hierarchy searches compare node volumes (internal to the broad phase): the overlap tests of two nodes'
// volumes that the descent takes for each pair of hierarchy volumes, and that of a box against a node's volume, which
// the moved-vertex queries descend on. Each is conservative: it never reports separation for volumes whose contents
// overlap (the OBB test widens its projected radii slightly to absorb rounding). Each takes the search's gap bound
// through `Reach` (Touching or WithinBound, gap_bound.hpp): with a bound, volumes within it of each other pass.
// The separations order a bounded search's node pairs, nearer first; any value would be correct there. The tests are
// forced inline: the descent calls them once per node pair, and GCC, left to itself, calls them out of line.

#include <cmath>

#include "broadphase/bvh.hpp"
#include "broadphase/gap_bound.hpp"
#include "broadphase/swept_boxes.hpp"

namespace clothcd::broadphase::detail {

/// The largest per-axis gap between two boxes (negative when they overlap): how far apart a bounded search takes them
/// to be when it orders node pairs.
[[nodiscard]] inline double box_separation(const FlatBox& a, const FlatBox& b) {
  double s = -HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    s = std::fmax(s, std::fmax(a.min[k] - b.max[k], b.min[k] - a.max[k]));
  }
  return s;
}

/// Node boxes against node boxes: AABB hierarchies, and the self search of sphere hierarchies.
template <class Reach>
struct BoxBox {
  const Bvh* a;  ///< Hierarchy of the first node.
  const Bvh* b;  ///< Hierarchy of the second node.
  Reach reach;   ///< The search's gap bound.
  /// Whether the tests read a gap bound (the descent then orders child pairs by separation()).
  static constexpr bool kBounded = Reach::kBounded;
  /// True when the boxes of node i of `a` and node j of `b` overlap (or are within the bound).
  [[gnu::always_inline]] bool operator()(int i, int j) const {
    return within(a->boxes()[i], b->boxes()[j], reach.gap());
  }
  /// How far apart the boxes are (box_separation).
  [[nodiscard]] double separation(int i, int j) const { return box_separation(a->boxes()[i], b->boxes()[j]); }
};

/// The double volume of sphere hierarchies at every node: the spheres first, the node boxes only when they overlap.
template <class Reach>
struct SphereThenBox {
  const Bvh* a;  ///< Hierarchy of the first node.
  const Bvh* b;  ///< Hierarchy of the second node.
  Reach reach;   ///< The search's gap bound.
  /// Whether the tests read a gap bound (the descent then orders child pairs by separation()).
  static constexpr bool kBounded = Reach::kBounded;
  /// True when the spheres and then the boxes of node i of `a` and node j of `b` overlap (or are within the bound).
  [[gnu::always_inline]] bool operator()(int i, int j) const {
    return within(a->spheres()[i], b->spheres()[j], reach.gap()) && within(a->boxes()[i], b->boxes()[j], reach.gap());
  }
  /// How far apart the boxes are (box_separation).
  [[nodiscard]] double separation(int i, int j) const { return box_separation(a->boxes()[i], b->boxes()[j]); }
};

/// Node boxes of the first hierarchy against node OBBs of the second (geometry/box_obb_overlap.hpp).
template <class Reach>
struct BoxObb {
  const Bvh* a;  ///< Hierarchy of the first node (AABB).
  const Bvh* b;  ///< Hierarchy of the second node (OBB).
  Reach reach;   ///< The search's gap bound.
  /// Whether the tests read a gap bound (the descent then orders child pairs by separation()).
  static constexpr bool kBounded = Reach::kBounded;
  /// True unless a separating axis parts the box of node i of `a` (grown by the bound) from the OBB of node j of `b`.
  [[gnu::always_inline]] bool operator()(int i, int j) const {
    return within(a->boxes()[i], b->obbs()[j], reach.gap());
  }
  /// The squared distance of the box's centre from the OBB's centre.
  [[nodiscard]] double separation(int i, int j) const {
    const FlatBox& box = a->boxes()[i];
    const Eigen::Vector3d centre(0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                                 0.5 * (box.min[2] + box.max[2]));
    return (centre - b->obbs()[j].center).squaredNorm();
  }
};

/// True when `box` overlaps (or is within `gap` of, gap_bound.hpp) the volume of node `n` of `bvh`: its node box, or
/// for an OBB hierarchy (which keeps no node boxes) its OBB.
template <class Gap>
bool box_overlaps_node(const FlatBox& box, const Bvh& bvh, int n, Gap gap) {
  return bvh.boxes().empty() ? within(box, bvh.obbs()[n], gap) : within(bvh.boxes()[n], box, gap);
}

}  // namespace clothcd::broadphase::detail
