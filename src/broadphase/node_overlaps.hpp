#pragma once
// How the hierarchy searches compare node volumes (internal to the broad phase): the overlap tests of two nodes'
// volumes that the descent takes for each pair of hierarchy volumes, and that of a box against a node's volume, which
// the moved-vertex queries descend on. Each is conservative: it never reports separation for volumes whose contents
// overlap (the OBB test widens its projected radii slightly to absorb rounding).

#include "broadphase/bvh.hpp"
#include "broadphase/swept_boxes.hpp"
#include "geometry/box_obb_overlap.hpp"

namespace clothcd::broadphase::detail {

/// Node boxes against node boxes: AABB hierarchies, and the self search of sphere hierarchies.
struct BoxBox {
  const Bvh* a;  ///< Hierarchy of the first node.
  const Bvh* b;  ///< Hierarchy of the second node.
  /// True when the boxes of node i of `a` and node j of `b` overlap.
  bool operator()(int i, int j) const { return a->boxes()[i].overlaps(b->boxes()[j]); }
};

/// The double volume of sphere hierarchies at every node: the spheres first, the node boxes only when they overlap.
struct SphereThenBox {
  const Bvh* a;  ///< Hierarchy of the first node.
  const Bvh* b;  ///< Hierarchy of the second node.
  /// True when the spheres and then the boxes of node i of `a` and node j of `b` overlap.
  bool operator()(int i, int j) const {
    return a->spheres()[i].overlaps(b->spheres()[j]) && a->boxes()[i].overlaps(b->boxes()[j]);
  }
};

/// Node boxes of the first hierarchy against node OBBs of the second (geometry/box_obb_overlap.hpp).
struct BoxObb {
  const Bvh* a;  ///< Hierarchy of the first node (AABB).
  const Bvh* b;  ///< Hierarchy of the second node (OBB).
  /// True unless a separating axis parts the box of node i of `a` from the OBB of node j of `b`.
  bool operator()(int i, int j) const {
    const FlatBox& box = a->boxes()[i];
    return geometry::box_obb_overlap(box.min, box.max, b->obbs()[j]);
  }
};

/// True when `box` overlaps the volume of node `n` of `bvh`: its node box, or for an OBB hierarchy (which keeps no
/// node boxes) its OBB.
inline bool box_overlaps_node(const FlatBox& box, const Bvh& bvh, int n) {
  return bvh.boxes().empty() ? geometry::box_obb_overlap(box.min, box.max, bvh.obbs()[n])
                             : bvh.boxes()[n].overlaps(box);
}

}  // namespace clothcd::broadphase::detail
