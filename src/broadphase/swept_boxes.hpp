#pragma once
/// @file
/// Swept bounding boxes of every primitive of a body over one step: each box bounds the primitive at t0 and at t1
/// (linear motion stays inside it) inflated by the thickness.

#include <cstdint>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "clothcd/geometry/bounding_volumes.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::broadphase {

/// Axis-aligned box in single flat storage, cheaper to test than geometry::Aabb in the hot loops.
struct FlatBox {
  double min[3];  ///< Lower corner.
  double max[3];  ///< Upper corner.

  /// True when the closed boxes share a point. All six comparisons are evaluated (no early exit): in the search's
  /// hot loops most tests fail on an unpredictable axis, and straight-line code avoids the mispredicted branches.
  [[nodiscard]] bool overlaps(const FlatBox& o) const {
    return (min[0] <= o.max[0]) & (o.min[0] <= max[0]) & (min[1] <= o.max[1]) & (o.min[1] <= max[1]) &
           (min[2] <= o.max[2]) & (o.min[2] <= max[2]);
  }
  /// Grows the box to contain `o`.
  void expand(const FlatBox& o) {
    for (int k = 0; k < 3; ++k) {
      min[k] = o.min[k] < min[k] ? o.min[k] : min[k];
      max[k] = o.max[k] > max[k] ? o.max[k] : max[k];
    }
  }
  /// The box as a geometry::Aabb.
  [[nodiscard]] geometry::Aabb to_aabb() const {
    geometry::Aabb b;
    b.min = Eigen::Vector3d(min[0], min[1], min[2]);
    b.max = Eigen::Vector3d(max[0], max[1], max[2]);
    return b;
  }
};

/// An empty box (min = +inf, max = -inf): expanding it by a box gives that box.
[[nodiscard]] FlatBox empty_flat_box();

/// Per-step swept boxes of one body; arrays are indexed like the body's vertices, edges and faces.
struct SweptBoxes {
  std::vector<FlatBox> vertices;  ///< #V boxes (vertices that no face uses get a box too; nothing reads it).
  std::vector<FlatBox> edges;     ///< #E boxes, union of the two vertex boxes.
  std::vector<FlatBox> faces;     ///< #F boxes, union of the three vertex boxes.
};

/// Fills `boxes` for positions `start` and `end` (#V x 3 each), reusing its storage, with every box inflated by half
/// of `thickness` (>= 0) on every side (rounded outwards): two primitives closer than the thickness at some instant
/// are closer than it along every axis, so their boxes, each grown by half of it, overlap.
/// Preconditions (checked by callers at the public boundary): matching sizes, finite coordinates.
void compute_swept_boxes(const BodyTopology& topology, const Vertices& start, const Vertices& end, double thickness,
                         SweptBoxes& boxes);

/// The vertex boxes only, as compute_swept_boxes computes them; `boxes.edges` and `boxes.faces` are left empty. Enough
/// for a Bvh (which derives edge and face boxes from the vertex boxes in its own order) and for body_box().
void compute_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness, SweptBoxes& boxes);

/// compute_swept_vertex_boxes over the part [from, to] of the step only (0 <= from < to <= 1): each vertex box bounds
/// the vertex's linear motion over t in [from, to] (its rounded positions at `from` and `to` moved outwards to cover
/// their rounding; a coordinate that does not move is kept exact). [0, 1] gives compute_swept_vertex_boxes' boxes.
void compute_part_vertex_boxes(const Vertices& start, const Vertices& end, double from, double to, double thickness,
                               SweptBoxes& boxes);

/// compute_swept_vertex_boxes for the vertices flagged in `moved` (non-zero, one flag per vertex) only: `boxes` must
/// hold the boxes of every other vertex for these positions already (from the same thickness), which it keeps.
void update_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness,
                               const std::vector<std::uint8_t>& moved, SweptBoxes& boxes);

}  // namespace clothcd::broadphase
