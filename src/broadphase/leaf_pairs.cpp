// Leaf-pair primitive tests (see leaf_pairs.hpp).
#include "broadphase/leaf_pairs.hpp"

#include <array>

#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/packed_boxes.hpp"

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

// For each 4-bit lane mask: the passing lanes in order (padded with lane 0) and how many there are.
struct LaneTable {
  std::array<std::array<int, 4>, 16> lanes{};
  std::array<int, 16> count{};
};

constexpr LaneTable make_lane_table() {
  LaneTable table;
  for (int mask = 0; mask < 16; ++mask) {
    for (int lane = 0; lane < 4; ++lane) {
      if ((mask >> lane) & 1) table.lanes[mask][table.count[mask]++] = lane;
    }
  }
  return table;
}

constexpr LaneTable kLaneTable = make_lane_table();

// The four-lane tests (the vector extension: SSE on x86-64, NEON on ARM), as bits (bit k for position j + k), and the
// masking of lanes past the end of a range.
struct FourLanes {
  static constexpr int kWidth = 4;
  static unsigned overlap(const PackedBoxes& boxes, int j, const PackedBox& q) {
    return lane_bits(boxes.overlap_lanes(j, q));
  }
  static unsigned edge_uses(const PackedVertexIds& ids, int j, int v, int w) {
    return lane_bits(ids.edge_uses_lanes(j, v, w));
  }
  static unsigned face_uses(const PackedVertexIds& ids, int j, int v) { return lane_bits(ids.face_uses_lanes(j, v)); }
  // `bits` without the lanes at or beyond `end` (a select, not a branch: the last group of a range is often short).
  static unsigned below(unsigned bits, int j, int end) {
    const int lanes = end - j < kWidth ? end - j : kWidth;
    return bits & ((1u << lanes) - 1u);
  }
  // Writes j + k for each set bit k of `mask` to out (all four slots written) and returns how many are set.
  static int write_passing(unsigned mask, int j, int* out) {
    const std::array<int, 4>& passing = kLaneTable.lanes[mask];
    for (int k = 0; k < 4; ++k) out[k] = j + passing[k];
    return kLaneTable.count[mask];
  }
};

#if defined(CLOTHCD_AVX2_PATHS)
// For each 8-bit lane mask: the passing lanes in order, as bytes (padded with lane 0).
constexpr std::array<std::array<std::uint8_t, 8>, 256> make_byte_lanes() {
  std::array<std::array<std::uint8_t, 8>, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    int count = 0;
    for (int lane = 0; lane < 8; ++lane) {
      if ((mask >> lane) & 1) table[mask][count++] = static_cast<std::uint8_t>(lane);
    }
  }
  return table;
}

constexpr std::array<std::array<std::uint8_t, 8>, 256> kByteLanes = make_byte_lanes();

// The eight-lane tests (AVX2, BMI2), as bits.
struct EightLanes {
  static constexpr int kWidth = 8;
  CLOTHCD_AVX2 static unsigned overlap(const PackedBoxes& boxes, int j, const PackedBox& q) {
    return boxes.overlap_bits8(j, q);
  }
  CLOTHCD_AVX2 static unsigned edge_uses(const PackedVertexIds& ids, int j, int v, int w) {
    return ids.edge_uses_bits8(j, v, w);
  }
  CLOTHCD_AVX2 static unsigned face_uses(const PackedVertexIds& ids, int j, int v) { return ids.face_uses_bits8(j, v); }
  CLOTHCD_AVX2 static unsigned below(unsigned bits, int j, int end) {
    return _bzhi_u32(bits, static_cast<unsigned>(end - j));  // end - j >= 8 keeps all eight
  }
  // Writes j + k for each set bit k of `mask` to out (all eight slots written, one store) and returns how many are set.
  CLOTHCD_AVX2 static int write_passing(unsigned mask, int j, int* out) {
    const __m256i lanes = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(kByteLanes[mask].data())));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_add_epi32(lanes, _mm256_set1_epi32(j)));
    return __builtin_popcount(mask);
  }
};
#endif

// Writes the positions j in [begin, end) whose bit is set in `bits(j)` (bit k for position j + k, evaluated
// Lanes::kWidth positions at a time) to `out` (grown as needed) and returns how many, without a data-dependent
// branch: each group's mask indexes a table of its passing lanes, every slot of the group is written, and the count
// advances by the number set.
template <class Lanes, class Bits>
int select_lanes(int begin, int end, std::vector<int>& out, const Bits& bits) {
  const auto needed = static_cast<std::size_t>(end - begin + Lanes::kWidth);
  if (out.size() < needed) out.resize(needed);
  int n = 0;
  for (int j = begin; j < end; j += Lanes::kWidth) n += Lanes::write_passing(Lanes::below(bits(j), j, end), j, &out[n]);
  return n;
}

// The positions j in [begin, end) whose packed box may overlap `q` (see select_lanes): every position whose
// double-precision box overlaps the box `q` was made from, and maybe a few more.
template <class Lanes>
int select_packed(const PackedBoxes& boxes, int begin, int end, const PackedBox& q, std::vector<int>& out) {
  return select_lanes<Lanes>(begin, end, out, [&](int j) { return Lanes::overlap(boxes, j, q); });
}

// Writes the positions j in [begin, end) that pass both tests to `out` (grown as needed) and returns how many:
// `bits(j)`, Lanes::kWidth positions at a time on packed data (bit k for position j + k; it may pass pairs that
// `confirm` rejects, never the reverse), then `confirm(j)`, the exact test, on the rare passes. (Here most groups pass
// nothing, so a loop over the set bits costs less than select_lanes' table writes.)
template <class Lanes, class Bits, class Confirm>
int collect_packed(int begin, int end, std::vector<int>& out, const Bits& bits, const Confirm& confirm) {
  if (out.size() < static_cast<std::size_t>(end - begin)) out.resize(static_cast<std::size_t>(end - begin));
  int n = 0;
  for (int j = begin; j < end; j += Lanes::kWidth) {
    unsigned mask = Lanes::below(bits(j), j, end);
    while (mask != 0) {
      const int k = j + __builtin_ctz(mask);
      mask &= mask - 1u;
      out[n] = k;
      n += confirm(k) ? 1 : 0;
    }
  }
  return n;
}

// The part of `range` from the first to the last position whose packed box may overlap `q` (empty when none may).
template <class Lanes>
Range near_span(const PackedBoxes& boxes, Range range, const PackedBox& q) {
  int first = range.end, last = range.begin - 1;
  for (int j = range.begin; j < range.end; j += Lanes::kWidth) {
    const unsigned bits = Lanes::below(Lanes::overlap(boxes, j, q), j, range.end);
    if (bits == 0) continue;
    if (first == range.end) first = j + __builtin_ctz(bits);
    last = j + 31 - __builtin_clz(bits);
  }
  return first == range.end ? Range{range.end, range.end} : Range{first, last + 1};
}

// Pairs each selected primitive i of a first set (scratch.selected[0..selected), positions in its tree-ordered arrays)
// with the positions j in range_of(i) of a second set whose boxes overlap i's box: the packed boxes Lanes::kWidth at a
// time, minus the lanes whose bits excluded_for(i)(j) sets (pairs that must not be produced), then the
// double-precision boxes. Calls emit(i, j) for each pair found and returns how many primitive pairs it looked at.
template <class Lanes, class RangeOf, class ExcludedFor, class Emit>
long pair_selected(const PackedBoxes& first_packed, const FlatBox* first_boxes, const PackedBoxes& second_packed,
                   const FlatBox* second_boxes, int selected, LeafScratch& scratch, const RangeOf& range_of,
                   const ExcludedFor& excluded_for, const Emit& emit) {
  long looked_at = 0;
  for (int k = 0; k < selected; ++k) {
    const int i = scratch.selected[k];
    const FlatBox& box = first_boxes[i];
    const PackedBox q = first_packed.at(i);
    const Range range = range_of(i);
    const auto excluded = excluded_for(i);
    looked_at += range.end - range.begin;
    const int hits = collect_packed<Lanes>(
        range.begin, range.end, scratch.hits,
        [&](int j) { return Lanes::overlap(second_packed, j, q) & ~excluded(j); },
        [&](int j) { return box.overlaps(second_boxes[j]); });
    for (int h = 0; h < hits; ++h) emit(i, scratch.hits[h]);
  }
  return looked_at;
}

// No pair excluded (primitives of different bodies never share a vertex).
auto exclude_none(int) {
  return [](int) { return 0u; };
}

// Primitive tests of two leaves of different bodies, Lanes::kWidth at a time. Boxes are read in tree order
// (contiguous per leaf); each primitive is first tested against the other leaf's box.
// With `moved` (flags per vertex of body a), only pairs with a moved vertex of body a are produced.
template <class Lanes>
void between_lanes(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                       CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  const BvhNode& la = ta.nodes()[na];
  const BvhNode& lb = tb.nodes()[nb];
  const PackedBox box_a = packed_leaf_box(ta, na), box_b = packed_leaf_box(tb, nb);
  // Whether the vertex at owned position i of the vertex body, or the face at tree position p of the face body, brings
  // a moved vertex of body a into the pair.
  auto wanted = [&](bool vertex_in_a, int i, int p) {
    if (moved == nullptr) return true;
    if (vertex_in_a) return moved[ta.owned_vertices()[i]] != 0;
    const int* f = ta.ordered_faces().data() + 3 * p;
    return moved[f[0]] != 0 || moved[f[1]] != 0 || moved[f[2]] != 0;
  };
  auto vertices_against_faces = [&](const BodyView& vertex_body, const BvhNode& vertex_leaf,
                                    const PackedBox& vertex_leaf_box, const BodyView& face_body,
                                    const BvhNode& face_leaf, const PackedBox& face_leaf_box) {
    const Bvh& tv = *vertex_body.bvh;
    const Bvh& tf = *face_body.bvh;
    const bool vertex_in_a = &vertex_body == &a;
    const FlatBox* vertex_boxes = tv.ordered_vertex_boxes().data();
    const FlatBox* face_boxes = tf.ordered_face_boxes().data();
    const Range vr = vertex_range(tv, vertex_leaf);
    const int selected = select_packed<Lanes>(tv.packed_vertex_boxes(), vr.begin, vr.end, face_leaf_box, scratch.selected);
    stats.primitive_tests += (vr.end - vr.begin);
    if (selected == 0) return;
    const Range faces = near_span<Lanes>(tf.packed_face_boxes(), Range{face_leaf.face_begin, face_leaf.face_end},
                                         vertex_leaf_box);
    stats.primitive_tests += face_leaf.face_end - face_leaf.face_begin;
    stats.primitive_tests += pair_selected<Lanes>(
        tv.packed_vertex_boxes(), vertex_boxes, tf.packed_face_boxes(), face_boxes, selected, scratch,
        [&](int) { return faces; }, exclude_none, [&](int i, int p) {
          if (wanted(vertex_in_a, i, p)) {
            out.vertex_face.push_back({vertex_body.body, tv.owned_vertices()[i], face_body.body, tf.face_order()[p]});
          }
        });
  };
  vertices_against_faces(a, la, box_a, b, lb, box_b);
  vertices_against_faces(b, lb, box_b, a, la, box_a);
  const Range ea = edge_range(ta, la), eb = edge_range(tb, lb);
  const int* edges_a = ta.ordered_edges().data();
  const FlatBox* edge_boxes_a = ta.ordered_edge_boxes().data();
  const FlatBox* edge_boxes_b = tb.ordered_edge_boxes().data();
  int selected = select_packed<Lanes>(ta.packed_edge_boxes(), ea.begin, ea.end, box_b, scratch.selected);
  if (moved != nullptr) {  // keep the edges with a moved vertex
    int kept = 0;
    for (int k = 0; k < selected; ++k) {
      const int i = scratch.selected[k];
      scratch.selected[kept] = i;
      kept += (moved[edges_a[2 * i]] | moved[edges_a[2 * i + 1]]) != 0 ? 1 : 0;
    }
    selected = kept;
  }
  stats.primitive_tests += (ea.end - ea.begin);
  if (selected == 0) return;
  const Range near_b = near_span<Lanes>(tb.packed_edge_boxes(), eb, box_a);
  stats.primitive_tests += (eb.end - eb.begin);
  stats.primitive_tests += pair_selected<Lanes>(
      ta.packed_edge_boxes(), edge_boxes_a, tb.packed_edge_boxes(), edge_boxes_b, selected, scratch,
      [&](int) { return near_b; }, exclude_none,
      [&](int i, int j) { out.edge_edge.push_back({a.body, ta.owned_edges()[i], b.body, tb.owned_edges()[j]}); });
}

// Primitive tests of two leaves (na != nb) of one body, or of one leaf (na == nb) against itself, Lanes::kWidth at a
// time. Each primitive is first tested against the other leaf's box; a pair passes when the boxes overlap and no
// vertex is shared. With `moved` (flags per vertex), only pairs with a moved vertex are produced.
template <class Lanes>
void within_lanes(const BodyView& body, int na, int nb, const std::uint8_t* moved, CandidateSet& out,
                      TraversalStats& stats, LeafScratch& scratch) {
  const Bvh& t = *body.bvh;
  const BvhNode& la = t.nodes()[na];
  const BvhNode& lb = t.nodes()[nb];
  const bool same = na == nb;
  const int* faces = t.ordered_faces().data();
  const int* edges = t.ordered_edges().data();
  const FlatBox* vertex_boxes = t.ordered_vertex_boxes().data();
  const FlatBox* face_boxes = t.ordered_face_boxes().data();
  const FlatBox* edge_boxes = t.ordered_edge_boxes().data();
  // Between two leaves, only the span of the face leaf's faces that may touch the vertex leaf's box is read.
  auto vertices_against_faces = [&](const BvhNode& vertex_leaf, const PackedBox& vertex_leaf_box,
                                    const BvhNode& face_leaf, const PackedBox& face_leaf_box) {
    const Range vr = vertex_range(t, vertex_leaf);
    const int selected = select_packed<Lanes>(t.packed_vertex_boxes(), vr.begin, vr.end, face_leaf_box, scratch.selected);
    stats.primitive_tests += (vr.end - vr.begin);
    if (selected == 0) return;
    const Range all_faces{face_leaf.face_begin, face_leaf.face_end};
    const Range near_faces = same ? all_faces : near_span<Lanes>(t.packed_face_boxes(), all_faces, vertex_leaf_box);
    stats.primitive_tests += same ? 0 : all_faces.end - all_faces.begin;
    stats.primitive_tests += pair_selected<Lanes>(
        t.packed_vertex_boxes(), vertex_boxes, t.packed_face_boxes(), face_boxes, selected, scratch,
        [&](int) { return near_faces; },
        [&](int i) {
          const int v = t.owned_vertices()[i];
          return [&ids = t.packed_faces(), v](int p) { return Lanes::face_uses(ids, p, v); };
        },
        [&](int i, int p) {
          const int v = t.owned_vertices()[i];
          const int* f = faces + 3 * p;
          if (moved == nullptr || moved[v] || moved[f[0]] || moved[f[1]] || moved[f[2]]) {
            out.vertex_face.push_back({body.body, v, body.body, t.face_order()[p]});
          }
        });
  };
  const PackedBox box_a = packed_leaf_box(t, na), box_b = packed_leaf_box(t, nb);
  vertices_against_faces(la, box_a, lb, box_b);
  if (!same) vertices_against_faces(lb, box_b, la, box_a);
  const Range ea = edge_range(t, la);
  const int selected = select_packed<Lanes>(t.packed_edge_boxes(), ea.begin, ea.end, box_b, scratch.selected);
  stats.primitive_tests += ea.end - ea.begin;
  if (selected == 0) return;
  const Range eb = same ? ea : near_span<Lanes>(t.packed_edge_boxes(), edge_range(t, lb), box_a);
  stats.primitive_tests += same ? 0 : edge_range(t, lb).end - edge_range(t, lb).begin;
  stats.primitive_tests += pair_selected<Lanes>(
      t.packed_edge_boxes(), edge_boxes, t.packed_edge_boxes(), edge_boxes, selected, scratch,
      [&](int i) { return Range{same ? i + 1 : eb.begin, eb.end}; },
      [&](int i) {
        const int a0 = edges[2 * i], a1 = edges[2 * i + 1];
        return [&ids = t.packed_edges(), a0, a1](int j) {
          return Lanes::edge_uses(ids, j, a0, a1);
        };
      },
      [&](int i, int j) {
        const int a0 = edges[2 * i], a1 = edges[2 * i + 1], b0 = edges[2 * j], b1 = edges[2 * j + 1];
        if (moved == nullptr || moved[a0] || moved[a1] || moved[b0] || moved[b1]) {
          const int e = t.owned_edges()[i], g = t.owned_edges()[j];
          out.edge_edge.push_back({body.body, e < g ? e : g, body.body, e < g ? g : e});
        }
      });
}

// leaf_primitives_overlapping, Lanes::kWidth primitives at a time.
template <class Lanes>
int overlapping_lanes(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box, const PackedBox& packed,
                       LeafScratch& scratch, std::vector<int>& out) {
  const BvhNode& node = bvh.nodes()[leaf];
  const Range range = kind == LeafPrimitives::Vertices ? vertex_range(bvh, node)
                      : kind == LeafPrimitives::Edges  ? edge_range(bvh, node)
                                                       : Range{node.face_begin, node.face_end};
  const PackedBoxes& packed_boxes = kind == LeafPrimitives::Vertices ? bvh.packed_vertex_boxes()
                                    : kind == LeafPrimitives::Edges  ? bvh.packed_edge_boxes()
                                                                     : bvh.packed_face_boxes();
  const FlatBox* boxes = kind == LeafPrimitives::Vertices ? bvh.ordered_vertex_boxes().data()
                         : kind == LeafPrimitives::Edges  ? bvh.ordered_edge_boxes().data()
                                                          : bvh.ordered_face_boxes().data();
  const int selected = select_packed<Lanes>(packed_boxes, range.begin, range.end, packed, scratch.selected);
  for (int k = 0; k < selected; ++k) {
    const int i = scratch.selected[k];
    if (boxes[i].overlaps(box)) out.push_back(i);
  }
  return range.end - range.begin;
}

#if defined(CLOTHCD_AVX2_PATHS)
// The eight-lane instantiations, compiled for AVX2 with every call inlined into them (so that no function compiled
// for the default target passes AVX2 vectors, and no AVX2 code leaks into shared inline functions).
__attribute__((target("avx2,bmi2"), flatten)) void between_wide(const BodyView& a, const BodyView& b, int na, int nb,
                                                           const std::uint8_t* moved, CandidateSet& out,
                                                           TraversalStats& stats, LeafScratch& scratch) {
  between_lanes<EightLanes>(a, b, na, nb, moved, out, stats, scratch);
}

__attribute__((target("avx2,bmi2"), flatten)) void within_wide(const BodyView& body, int na, int nb,
                                                          const std::uint8_t* moved, CandidateSet& out,
                                                          TraversalStats& stats, LeafScratch& scratch) {
  within_lanes<EightLanes>(body, na, nb, moved, out, stats, scratch);
}

__attribute__((target("avx2,bmi2"), flatten)) int overlapping_wide(const Bvh& bvh, int leaf, LeafPrimitives kind,
                                                              const FlatBox& box, const PackedBox& packed,
                                                              LeafScratch& scratch, std::vector<int>& out) {
  return overlapping_lanes<EightLanes>(bvh, leaf, kind, box, packed, scratch, out);
}
#endif

}  // namespace

int leaf_primitives_overlapping(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                const PackedBox& packed, LeafScratch& scratch, std::vector<int>& out) {
#if defined(CLOTHCD_AVX2_PATHS)
  if (scratch.wide_lanes) return overlapping_wide(bvh, leaf, kind, box, packed, scratch, out);
#endif
  return overlapping_lanes<FourLanes>(bvh, leaf, kind, box, packed, scratch, out);
}

void leaf_pair_between(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                       CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
#if defined(CLOTHCD_AVX2_PATHS)
  if (scratch.wide_lanes) return between_wide(a, b, na, nb, moved, out, stats, scratch);
#endif
  between_lanes<FourLanes>(a, b, na, nb, moved, out, stats, scratch);
}

void leaf_pair_within(const BodyView& body, int na, int nb, const std::uint8_t* moved, CandidateSet& out,
                      TraversalStats& stats, LeafScratch& scratch) {
#if defined(CLOTHCD_AVX2_PATHS)
  if (scratch.wide_lanes) return within_wide(body, na, nb, moved, out, stats, scratch);
#endif
  within_lanes<FourLanes>(body, na, nb, moved, out, stats, scratch);
}

}  // namespace clothcd::broadphase::detail
