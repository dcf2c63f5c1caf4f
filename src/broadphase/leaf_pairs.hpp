#pragma once
// The primitive tests of one pair of overlapping leaves (internal to the broad phase): vertices against faces and
// edges against edges by their swept boxes, or faces against faces, producing candidate pairs. Each primitive is first
// pre-selected against the other leaf's box, then tested against the other leaf's primitives (of two different leaves,
// only the span of them from the first to the last that may touch the first leaf's box) four (or, from
// SimdLevel::Avx2 up, eight) at a time on packed single-precision boxes (and, within one body, packed vertex indices to
// skip pairs that share a vertex); the few passes are confirmed on the double-precision boxes, so the output is
// exactly that of the box tests. With a gap bound (TraversalSettings::gap_bound), every test passes boxes within its
// current value (gap_bound.hpp), read once per leaf for the tests against the other leaf's box and once per primitive
// for its tests against the other leaf's primitives.

#include <atomic>
#include <cstdint>
#include <vector>

#include "broadphase/candidates.hpp"
#include "broadphase/gap_bound.hpp"
#include "broadphase/packed_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "support/simd_level.hpp"

namespace clothcd::broadphase::detail {

/// Lists of one search task, reused from leaf pair to leaf pair.
struct LeafScratch {
  SimdLevel level = SimdLevel::Baseline;  ///< The level the lane tests run at (eight lanes from Avx2 up, else four)
  std::vector<int> selected;  ///< Primitives of one leaf whose box overlaps the other leaf's box
  std::vector<int> hits;      ///< Primitives of the other leaf that pass every test against one selected primitive
};

/// The primitives a leaf holds, by kind.
enum class LeafPrimitives {
  Vertices,  ///< Its owned vertices (positions in Bvh::owned_vertices).
  Edges,     ///< Its owned edges (positions in Bvh::owned_edges).
  Faces,     ///< Its faces (positions in Bvh::face_order).
};

/// Appends to `out` the positions of the primitives of kind `kind` in leaf `leaf` of `bvh` whose swept box overlaps
/// `box` (`packed` = pack_box(box)): the packed pre-selection, then the double-precision boxes, so exactly those.
/// Returns how many primitives of that kind the leaf holds (the tests made).
int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, NoGap gap, LeafScratch& scratch, std::vector<int>& out);

/// leaf_primitives_overlapping for the primitives whose swept box is within `gap` (>= 0) of `box` (gap_bound.hpp;
/// `packed` = packed_reach(box, pack_box(box), gap)).
int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, double gap, LeafScratch& scratch, std::vector<int>& out);

/// Candidate pairs of leaf `na` of body a and leaf `nb` of body b (different bodies) into `out`. With `moved` (flags
/// per vertex of body a), only pairs with a moved vertex of body a are produced. With `gap_bound`, the pairs within
/// its value (TraversalSettings::gap_bound).
void leaf_pair_between(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                       const std::atomic<double>* gap_bound, CandidateSet& out, TraversalStats& stats,
                       LeafScratch& scratch);

/// Candidate pairs of leaves `na` and `nb` of one body (na == nb: the leaf against itself), skipping pairs that share
/// a vertex. With `moved` (flags per vertex), only pairs with a moved vertex are produced. With `gap_bound`, the pairs
/// within its value.
void leaf_pair_within(const BodyView& body, int na, int nb, const std::uint8_t* moved,
                      const std::atomic<double>* gap_bound, CandidateSet& out, TraversalStats& stats,
                      LeafScratch& scratch);

/// Face pairs (CandidateSet::face_face) of leaf `na` of body a and leaf `nb` of body b (different bodies, a.body <
/// b.body) into `out`: every face of one against every face of the other whose boxes overlap (with `gap_bound`: are
/// within its value).
void leaf_face_pairs_between(const BodyView& a, const BodyView& b, int na, int nb, const std::atomic<double>* gap_bound,
                             CandidateSet& out, TraversalStats& stats, LeafScratch& scratch);

/// Face pairs of leaves `na` and `nb` of one body (na == nb: the leaf against itself) into `out`, faces sharing
/// vertices included, each pair once with face_a < face_b, never a face with itself. With `gap_bound`, the pairs
/// within its value.
void leaf_face_pairs_within(const BodyView& body, int na, int nb, const std::atomic<double>* gap_bound,
                            CandidateSet& out, TraversalStats& stats, LeafScratch& scratch);

/// The lanes one packed test covers at `level`: 8 from SimdLevel::Avx2 up, else 4.
[[nodiscard]] int packed_lane_width(SimdLevel level);

/// Bit k set when packed box j + k may overlap `q` (k < packed_lane_width(level)): set whenever the double-precision
/// boxes overlap, never in the padding. Requires 0 <= j < boxes.size(). The lane test of the kernels, for tests.
[[nodiscard]] unsigned packed_overlap_bits(SimdLevel level, const PackedBoxes& boxes, int j, const PackedBox& q);

/// Bit k set when edge j + k of the edge rows `ids` uses vertex `v` or `w` (>= 0); never in the padding.
[[nodiscard]] unsigned packed_edge_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v, int w);

/// Bit k set when face j + k of the face rows `ids` uses vertex `v` (>= 0); never in the padding.
[[nodiscard]] unsigned packed_face_uses_bits(SimdLevel level, const PackedVertexIds& ids, int j, int v);

}  // namespace clothcd::broadphase::detail
