// Leaf-pair primitive tests (see leaf_pairs.hpp).
#include "broadphase/leaf_pairs.hpp"

#include <array>
#include <cstdint>
#include <vector>

#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/packed_boxes.hpp"
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

// The leaf's box as an outward-rounded float box: the packed node box, or packed from leaf_box() for OBB hierarchies.
PackedBox packed_leaf_box(const Bvh& bvh, int node) {
  if (bvh.packed_node_boxes().size() > 0) return bvh.packed_node_boxes().at(node);
  return pack_box(leaf_box(bvh, node));
}

// No pair excluded (primitives of different bodies never share a vertex).
auto exclude_none(int) {
  return [](int) { return 0u; };
}

// The kernels, once per width: four lanes (the baseline), and eight compiled for AVX2.
namespace four {
namespace lanes = simd::w4;
#include "broadphase/leaf_pair_lanes.hpp"
}  // namespace four

#if defined(CLOTHCD_SIMD_X86)
CLOTHCD_SIMD_BEGIN_AVX2
namespace eight {
namespace lanes = simd::w8;
#include "broadphase/leaf_pair_lanes.hpp"
}  // namespace eight

// The entry points of the eight-lane kernels, with every call inlined into them (so that no AVX2 code leaks into
// inline functions shared with the baseline).
__attribute__((flatten)) void between_wide(const BodyView& a, const BodyView& b, int na, int nb,
                                           const std::uint8_t* moved, CandidateSet& out, TraversalStats& stats,
                                           LeafScratch& scratch) {
  eight::between_lanes(a, b, na, nb, moved, out, stats, scratch);
}

__attribute__((flatten)) void within_wide(const BodyView& body, int na, int nb, const std::uint8_t* moved,
                                          CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
  eight::within_lanes(body, na, nb, moved, out, stats, scratch);
}

__attribute__((flatten)) int overlapping_wide(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                              const PackedBox& packed, LeafScratch& scratch, std::vector<int>& out) {
  return eight::overlapping_lanes(bvh, leaf, kind, box, packed, scratch, out);
}

unsigned overlap_bits_wide(const PackedBoxes& boxes, int j, const PackedBox& q) {
  return eight::overlap_bits(boxes, j, q);
}

unsigned edge_uses_bits_wide(const PackedVertexIds& ids, int j, int v, int w) {
  return eight::edge_uses_bits(ids, j, v, w);
}

unsigned face_uses_bits_wide(const PackedVertexIds& ids, int j, int v) { return eight::face_uses_bits(ids, j, v); }
CLOTHCD_SIMD_END
#endif

// Whether `level` runs the eight-lane kernels.
bool eight_lanes(SimdLevel level) {
#if defined(CLOTHCD_SIMD_X86)
  return level >= SimdLevel::Avx2;
#else
  (void)level;
  return false;
#endif
}

}  // namespace

int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, LeafScratch& scratch, std::vector<int>& out) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(scratch.level)) return overlapping_wide(bvh, leaf, kind, box, packed, scratch, out);
#endif
  return four::overlapping_lanes(bvh, leaf, kind, box, packed, scratch, out);
}

void leaf_pair_between(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                       CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(scratch.level)) return between_wide(a, b, na, nb, moved, out, stats, scratch);
#endif
  four::between_lanes(a, b, na, nb, moved, out, stats, scratch);
}

void leaf_pair_within(const BodyView& body, int na, int nb, const std::uint8_t* moved, CandidateSet& out,
                      TraversalStats& stats, LeafScratch& scratch) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(scratch.level)) return within_wide(body, na, nb, moved, out, stats, scratch);
#endif
  four::within_lanes(body, na, nb, moved, out, stats, scratch);
}

int packed_lane_width(SimdLevel level) { return eight_lanes(level) ? 8 : 4; }

unsigned packed_overlap_bits(SimdLevel level, const PackedBoxes& boxes, int j, const PackedBox& q) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(level)) return overlap_bits_wide(boxes, j, q);
#endif
  (void)level;
  return four::overlap_bits(boxes, j, q);
}

unsigned packed_edge_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v, int w) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(level)) return edge_uses_bits_wide(ids, j, v, w);
#endif
  (void)level;
  return four::edge_uses_bits(ids, j, v, w);
}

unsigned packed_face_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v) {
#if defined(CLOTHCD_SIMD_X86)
  if (eight_lanes(level)) return face_uses_bits_wide(ids, j, v);
#endif
  (void)level;
  return four::face_uses_bits(ids, j, v);
}

}  // namespace clothcd::broadphase::detail
