// Leaf-pair primitive tests (see leaf_pairs.hpp).
#include "broadphase/leaf_pairs.hpp"

#include <array>
#include <cstdint>
#include <vector>

#include "broadphase/bvh.hpp"
#include "broadphase/gap_bound.hpp"
#include "broadphase/packed_boxes.hpp"
#include "support/simd.hpp"

namespace clothcd::broadphase::detail {
namespace {

struct Range {
  int begin;
  int end;
};

Range vertex_range(const Bvh& bvh, const BvhNode& node) {
  return {bvh.vertex_offset()[node.face_begin], bvh.vertex_offset()[node.face_end]};
}
Range edge_range(const Bvh& bvh, const BvhNode& node) {
  return {bvh.edge_offset()[node.face_begin], bvh.edge_offset()[node.face_end]};
}

// Union of the swept boxes of a leaf's triangles. It bounds every primitive the leaf owns (a vertex or edge box lies
// inside the box of its owning triangle), so a primitive that misses it misses every primitive of the leaf. AABB and
// sphere hierarchies store it as the node box.
FlatBox leaf_box(const Bvh& bvh, int node) {
  if (!bvh.boxes().empty()) return bvh.boxes()[node];
  const BvhNode& leaf = bvh.nodes()[node];
  FlatBox b = empty_flat_box();
  for (int p = leaf.face_begin; p < leaf.face_end; ++p) b.expand(bvh.ordered_face_boxes()[p]);
  return b;
}

// The query of the other leaf's primitives by leaf `node`'s box, as an outward-rounded float box: the packed node box,
// or packed from leaf_box() for OBB hierarchies.
PackedBox leaf_query(const Bvh& bvh, int node, NoGap) {
  if (bvh.packed_node_boxes().size() > 0) return bvh.packed_node_boxes().at(node);
  return pack_box(leaf_box(bvh, node));
}

// The query by leaf `node`'s box within `gap` (packed_reach).
PackedBox leaf_query(const Bvh& bvh, int node, double gap) { return pack_box(reach_box(leaf_box(bvh, node), gap)); }

// No pair excluded (primitives of different bodies never share a vertex).
auto exclude_none(int) {
  return [](int) { return 0u; };
}

// The kernels, once per level: four lanes at the baseline, eight from AVX2 up.
#define CLOTHCD_SIMD_KERNEL "broadphase/leaf_pair_lanes.hpp"
#include "support/simd_versions.hpp"

}  // namespace

int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, NoGap gap, LeafScratch& scratch, std::vector<int>& out) {
  return CLOTHCD_SIMD_DISPATCH(scratch.level, overlapping_lanes(bvh, leaf, kind, box, packed, gap, scratch, out));
}

int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, double gap, LeafScratch& scratch, std::vector<int>& out) {
  return CLOTHCD_SIMD_DISPATCH(scratch.level, overlapping_lanes(bvh, leaf, kind, box, packed, gap, scratch, out));
}

// Each leaf pair takes the kernel of the search's kind, with or without a gap bound: one branch per leaf pair.
void leaf_pair_between(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                       const std::atomic<double>* gap_bound, CandidateSet& out, TraversalStats& stats,
                       LeafScratch& scratch) {
  if (gap_bound == nullptr) {
    CLOTHCD_SIMD_DISPATCH(scratch.level, between_lanes(a, b, na, nb, moved, Touching{}, out, stats, scratch));
  } else {
    CLOTHCD_SIMD_DISPATCH(scratch.level,
                          between_lanes(a, b, na, nb, moved, WithinBound{gap_bound}, out, stats, scratch));
  }
}

void leaf_pair_within(const BodyView& body, int na, int nb, const std::uint8_t* moved,
                      const std::atomic<double>* gap_bound, CandidateSet& out, TraversalStats& stats,
                      LeafScratch& scratch) {
  if (gap_bound == nullptr) {
    CLOTHCD_SIMD_DISPATCH(scratch.level, within_lanes(body, na, nb, moved, Touching{}, out, stats, scratch));
  } else {
    CLOTHCD_SIMD_DISPATCH(scratch.level,
                          within_lanes(body, na, nb, moved, WithinBound{gap_bound}, out, stats, scratch));
  }
}

void leaf_face_pairs_between(const BodyView& a, const BodyView& b, int na, int nb, const std::atomic<double>* gap_bound,
                             CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
  if (gap_bound == nullptr) {
    CLOTHCD_SIMD_DISPATCH(scratch.level, face_pairs_between_lanes(a, b, na, nb, Touching{}, out, stats, scratch));
  } else {
    CLOTHCD_SIMD_DISPATCH(scratch.level,
                          face_pairs_between_lanes(a, b, na, nb, WithinBound{gap_bound}, out, stats, scratch));
  }
}

void leaf_face_pairs_within(const BodyView& body, int na, int nb, const std::atomic<double>* gap_bound,
                            CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
  if (gap_bound == nullptr) {
    CLOTHCD_SIMD_DISPATCH(scratch.level, face_pairs_within_lanes(body, na, nb, Touching{}, out, stats, scratch));
  } else {
    CLOTHCD_SIMD_DISPATCH(scratch.level,
                          face_pairs_within_lanes(body, na, nb, WithinBound{gap_bound}, out, stats, scratch));
  }
}

int packed_lane_width(SimdLevel level) { return CLOTHCD_SIMD_DISPATCH(level, lanes::kFloatLanes); }

unsigned packed_overlap_bits(SimdLevel level, const PackedBoxes& boxes, int j, const PackedBox& q) {
  return CLOTHCD_SIMD_DISPATCH(level, overlap_bits(boxes, j, q));
}

unsigned packed_edge_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v, int w) {
  return CLOTHCD_SIMD_DISPATCH(level, edge_uses_bits(ids, j, v, w));
}

unsigned packed_face_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v) {
  return CLOTHCD_SIMD_DISPATCH(level, face_uses_bits(ids, j, v));
}

}  // namespace clothcd::broadphase::detail
