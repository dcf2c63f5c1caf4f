// The leaf-pair kernels of leaf_pairs.cpp, written once on the vector layer (support/simd.hpp) and compiled there
// once per level by support/simd_versions.hpp (four lanes at the baseline, eight from AVX2 up), after the standard
// headers and the width-independent helpers (Range, vertex_range, edge_range, leaf_query, exclude_none). The kernels
// take the search's gap bound as `Reach` (Touching or WithinBound, gap_bound.hpp) and each test's gap from it.
// No include guard and no includes of its own, on purpose.

// The lane tests on packed data, as bits (bit k for position j + k).

// Lane k: box j + k may overlap `q` (true whenever the double-precision boxes overlap; false in the padding).
inline unsigned overlap_bits(const PackedBoxes& boxes, int j, const PackedBox& q) {
  const float* r = boxes.rows() + j;
  const int s = boxes.stride();
  return lanes::bits((q.lo[0] <= lanes::load(r + 3 * s)) & (lanes::load(r) <= q.hi[0]) &
                     (q.lo[1] <= lanes::load(r + 4 * s)) & (lanes::load(r + s) <= q.hi[1]) &
                     (q.lo[2] <= lanes::load(r + 5 * s)) & (lanes::load(r + 2 * s) <= q.hi[2]));
}

// Lane k: edge j + k uses vertex `v` or `w` (>= 0); false in the padding. Edge rows only.
inline unsigned edge_uses_bits(const PackedVertexIds& ids, int j, int v, int w) {
  const lanes::Ints first = lanes::load(ids.rows() + j), second = lanes::load(ids.rows() + j + ids.stride());
  return lanes::bits((first == v) | (second == v) | (first == w) | (second == w));
}

// Lane k: face j + k uses vertex `v` (>= 0); false in the padding. Face rows only.
inline unsigned face_uses_bits(const PackedVertexIds& ids, int j, int v) {
  const int* r = ids.rows() + j;
  const int s = ids.stride();
  return lanes::bits((lanes::load(r) == v) | (lanes::load(r + s) == v) | (lanes::load(r + 2 * s) == v));
}

// `bits` without the lanes at or beyond `end` (a select, not a branch: the last group of a range is often short).
inline unsigned below(unsigned bits, int j, int end) { return lanes::bits_below(bits, end - j); }

// For each lane mask: the passing lanes in order, as bytes (padded with lane 0), and how many there are.
struct PassingLanes {
  std::array<std::array<std::uint8_t, lanes::kFloatLanes>, (1u << lanes::kFloatLanes)> lanes{};
  std::array<int, (1u << lanes::kFloatLanes)> count{};
};

constexpr PassingLanes make_passing_lanes() {
  PassingLanes table;
  for (unsigned mask = 0; mask < (1u << lanes::kFloatLanes); ++mask) {
    for (int lane = 0; lane < lanes::kFloatLanes; ++lane) {
      if ((mask >> lane) & 1u) table.lanes[mask][table.count[mask]++] = static_cast<std::uint8_t>(lane);
    }
  }
  return table;
}

constexpr PassingLanes kPassingLanes = make_passing_lanes();

// Writes j + k for each set bit k of `mask` to out (all kFloatLanes slots written) and returns how many are set.
inline int write_passing(unsigned mask, int j, int* out) {
  lanes::widen_add(kPassingLanes.lanes[mask].data(), j, out);
  return kPassingLanes.count[mask];
}

// Writes the positions j in [begin, end) whose bit is set in `bits(j)` (bit k for position j + k, evaluated
// lanes::kFloatLanes positions at a time) to `out` (grown as needed) and returns how many, without a data-dependent
// branch: each group's mask indexes a table of its passing lanes, every slot of the group is written, and the count
// advances by the number set.
template <class Bits>
int select_lanes(int begin, int end, std::vector<int>& out, const Bits& bits) {
  const auto needed = static_cast<std::size_t>(end - begin + lanes::kFloatLanes);
  if (out.size() < needed) out.resize(needed);
  int n = 0;
  for (int j = begin; j < end; j += lanes::kFloatLanes) n += write_passing(below(bits(j), j, end), j, &out[n]);
  return n;
}

// The positions j in [begin, end) whose packed box may overlap `q` (see select_lanes): every position whose
// double-precision box overlaps the box `q` was made from, and maybe a few more.
int select_packed(const PackedBoxes& boxes, int begin, int end, const PackedBox& q, std::vector<int>& out) {
  return select_lanes(begin, end, out, [&](int j) { return overlap_bits(boxes, j, q); });
}

// Writes the positions j in [begin, end) that pass both tests to `out` (grown as needed) and returns how many:
// `bits(j)`, lanes::kFloatLanes positions at a time on packed data (bit k for position j + k; it may pass pairs that
// `confirm` rejects, never the reverse), then `confirm(j)`, the exact test, on the rare passes. (Here most groups pass
// nothing, so a loop over the set bits costs less than select_lanes' table writes.)
template <class Bits, class Confirm>
int collect_packed(int begin, int end, std::vector<int>& out, const Bits& bits, const Confirm& confirm) {
  if (out.size() < static_cast<std::size_t>(end - begin)) out.resize(static_cast<std::size_t>(end - begin));
  int n = 0;
  for (int j = begin; j < end; j += lanes::kFloatLanes) {
    unsigned mask = below(bits(j), j, end);
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
Range near_span(const PackedBoxes& boxes, Range range, const PackedBox& q) {
  int first = range.end, last = range.begin - 1;
  for (int j = range.begin; j < range.end; j += lanes::kFloatLanes) {
    const unsigned bits = below(overlap_bits(boxes, j, q), j, range.end);
    if (bits == 0) continue;
    if (first == range.end) first = j + __builtin_ctz(bits);
    last = j + 31 - __builtin_clz(bits);
  }
  return first == range.end ? Range{range.end, range.end} : Range{first, last + 1};
}

// Pairs each selected primitive i of a first set (scratch.selected[0..selected), positions in its tree-ordered arrays)
// with the positions j in range_of(i) of a second set whose boxes overlap i's box (are within the gap of it): the
// packed boxes lanes::kFloatLanes at a time, minus the lanes whose bits excluded_for(i)(j) sets (pairs that must not
// be produced), then the double-precision boxes. Calls emit(i, j) for each pair found and returns how many primitive
// pairs it looked at.
template <class Reach, class RangeOf, class ExcludedFor, class Emit>
long pair_selected(const PackedBoxes& first_packed, const FlatBox* first_boxes, const PackedBoxes& second_packed,
                   const FlatBox* second_boxes, int selected, const Reach& reach, LeafScratch& scratch,
                   const RangeOf& range_of, const ExcludedFor& excluded_for, const Emit& emit) {
  long looked_at = 0;
  for (int k = 0; k < selected; ++k) {
    const int i = scratch.selected[k];
    const FlatBox& box = first_boxes[i];
    const auto gap = reach.gap();
    const PackedBox q = packed_reach(box, first_packed.at(i), gap);
    const Range range = range_of(i);
    const auto excluded = excluded_for(i);
    looked_at += range.end - range.begin;
    const int hits = collect_packed(
        range.begin, range.end, scratch.hits,
        [&](int j) { return overlap_bits(second_packed, j, q) & ~excluded(j); },
        [&](int j) { return within(box, second_boxes[j], gap); });
    for (int h = 0; h < hits; ++h) emit(i, scratch.hits[h]);
  }
  return looked_at;
}

// Primitive tests of two leaves of different bodies, lanes::kFloatLanes at a time. Boxes are read in tree order
// (contiguous per leaf); each primitive is first tested against the other leaf's box.
// With `moved` (flags per vertex of body a), only pairs with a moved vertex of body a are produced.
template <class Reach>
CLOTHCD_SIMD_ENTRY void between_lanes(const BodyView& a, const BodyView& b, int na, int nb, const std::uint8_t* moved,
                                      const Reach& reach, CandidateSet& out, TraversalStats& stats,
                                      LeafScratch& scratch) {
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  const BvhNode& la = ta.nodes()[na];
  const BvhNode& lb = tb.nodes()[nb];
  const auto gap = reach.gap();
  const PackedBox box_a = leaf_query(ta, na, gap), box_b = leaf_query(tb, nb, gap);
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
    const int selected = select_packed(tv.packed_vertex_boxes(), vr.begin, vr.end, face_leaf_box, scratch.selected);
    stats.primitive_tests += (vr.end - vr.begin);
    if (selected == 0) return;
    const Range faces = near_span(tf.packed_face_boxes(), Range{face_leaf.face_begin, face_leaf.face_end},
                                         vertex_leaf_box);
    stats.primitive_tests += face_leaf.face_end - face_leaf.face_begin;
    stats.primitive_tests += pair_selected(
        tv.packed_vertex_boxes(), vertex_boxes, tf.packed_face_boxes(), face_boxes, selected, reach, scratch,
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
  int selected = select_packed(ta.packed_edge_boxes(), ea.begin, ea.end, box_b, scratch.selected);
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
  const Range near_b = near_span(tb.packed_edge_boxes(), eb, box_a);
  stats.primitive_tests += (eb.end - eb.begin);
  stats.primitive_tests += pair_selected(
      ta.packed_edge_boxes(), edge_boxes_a, tb.packed_edge_boxes(), edge_boxes_b, selected, reach, scratch,
      [&](int) { return near_b; }, exclude_none,
      [&](int i, int j) { out.edge_edge.push_back({a.body, ta.owned_edges()[i], b.body, tb.owned_edges()[j]}); });
}

// Primitive tests of two leaves (na != nb) of one body, or of one leaf (na == nb) against itself, lanes::kFloatLanes at a
// time. Each primitive is first tested against the other leaf's box; a pair passes when the boxes overlap and no
// vertex is shared. With `moved` (flags per vertex), only pairs with a moved vertex are produced.
template <class Reach>
CLOTHCD_SIMD_ENTRY void within_lanes(const BodyView& body, int na, int nb, const std::uint8_t* moved,
                                     const Reach& reach, CandidateSet& out, TraversalStats& stats,
                                     LeafScratch& scratch) {
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
    const int selected = select_packed(t.packed_vertex_boxes(), vr.begin, vr.end, face_leaf_box, scratch.selected);
    stats.primitive_tests += (vr.end - vr.begin);
    if (selected == 0) return;
    const Range all_faces{face_leaf.face_begin, face_leaf.face_end};
    const Range near_faces = same ? all_faces : near_span(t.packed_face_boxes(), all_faces, vertex_leaf_box);
    stats.primitive_tests += same ? 0 : all_faces.end - all_faces.begin;
    stats.primitive_tests += pair_selected(
        t.packed_vertex_boxes(), vertex_boxes, t.packed_face_boxes(), face_boxes, selected, reach, scratch,
        [&](int) { return near_faces; },
        [&](int i) {
          const int v = t.owned_vertices()[i];
          return [&ids = t.packed_faces(), v](int p) { return face_uses_bits(ids, p, v); };
        },
        [&](int i, int p) {
          const int v = t.owned_vertices()[i];
          const int* f = faces + 3 * p;
          if (moved == nullptr || moved[v] || moved[f[0]] || moved[f[1]] || moved[f[2]]) {
            out.vertex_face.push_back({body.body, v, body.body, t.face_order()[p]});
          }
        });
  };
  const auto gap = reach.gap();
  const PackedBox box_a = leaf_query(t, na, gap), box_b = leaf_query(t, nb, gap);
  vertices_against_faces(la, box_a, lb, box_b);
  if (!same) vertices_against_faces(lb, box_b, la, box_a);
  const Range ea = edge_range(t, la);
  const int selected = select_packed(t.packed_edge_boxes(), ea.begin, ea.end, box_b, scratch.selected);
  stats.primitive_tests += ea.end - ea.begin;
  if (selected == 0) return;
  const Range eb = same ? ea : near_span(t.packed_edge_boxes(), edge_range(t, lb), box_a);
  stats.primitive_tests += same ? 0 : edge_range(t, lb).end - edge_range(t, lb).begin;
  stats.primitive_tests += pair_selected(
      t.packed_edge_boxes(), edge_boxes, t.packed_edge_boxes(), edge_boxes, selected, reach, scratch,
      [&](int i) { return Range{same ? i + 1 : eb.begin, eb.end}; },
      [&](int i) {
        const int a0 = edges[2 * i], a1 = edges[2 * i + 1];
        return [&ids = t.packed_edges(), a0, a1](int j) {
          return edge_uses_bits(ids, j, a0, a1);
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

// Face pairs of two leaves of different bodies, lanes::kFloatLanes at a time: each face of `na` is first tested against
// the other leaf's box, then against the span of the other leaf's faces that may touch this leaf's box.
template <class Reach>
CLOTHCD_SIMD_ENTRY void face_pairs_between_lanes(const BodyView& a, const BodyView& b, int na, int nb,
                                                 const Reach& reach, CandidateSet& out, TraversalStats& stats,
                                                 LeafScratch& scratch) {
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  const BvhNode& la = ta.nodes()[na];
  const BvhNode& lb = tb.nodes()[nb];
  const auto gap = reach.gap();
  const PackedBox box_a = leaf_query(ta, na, gap), box_b = leaf_query(tb, nb, gap);
  const int selected = select_packed(ta.packed_face_boxes(), la.face_begin, la.face_end, box_b, scratch.selected);
  stats.primitive_tests += la.face_end - la.face_begin;
  if (selected == 0) return;
  const Range near_b = near_span(tb.packed_face_boxes(), Range{lb.face_begin, lb.face_end}, box_a);
  stats.primitive_tests += lb.face_end - lb.face_begin;
  stats.primitive_tests += pair_selected(
      ta.packed_face_boxes(), ta.ordered_face_boxes().data(), tb.packed_face_boxes(), tb.ordered_face_boxes().data(),
      selected, reach, scratch, [&](int) { return near_b; }, exclude_none,
      [&](int i, int j) { out.face_face.push_back({a.body, ta.face_order()[i], b.body, tb.face_order()[j]}); });
}

// Face pairs of two leaves (na != nb) of one body, or of one leaf (na == nb) against itself (each face against the
// later ones), lanes::kFloatLanes at a time; faces sharing vertices are paired too.
template <class Reach>
CLOTHCD_SIMD_ENTRY void face_pairs_within_lanes(const BodyView& body, int na, int nb, const Reach& reach,
                                                CandidateSet& out, TraversalStats& stats, LeafScratch& scratch) {
  const Bvh& t = *body.bvh;
  const BvhNode& la = t.nodes()[na];
  const BvhNode& lb = t.nodes()[nb];
  const bool same = na == nb;
  const auto gap = reach.gap();
  const PackedBox box_a = leaf_query(t, na, gap), box_b = leaf_query(t, nb, gap);
  const int selected = select_packed(t.packed_face_boxes(), la.face_begin, la.face_end, box_b, scratch.selected);
  stats.primitive_tests += la.face_end - la.face_begin;
  if (selected == 0) return;
  const Range all_b{lb.face_begin, lb.face_end};
  const Range near_b = same ? all_b : near_span(t.packed_face_boxes(), all_b, box_a);
  stats.primitive_tests += same ? 0 : all_b.end - all_b.begin;
  const FlatBox* boxes = t.ordered_face_boxes().data();
  stats.primitive_tests += pair_selected(
      t.packed_face_boxes(), boxes, t.packed_face_boxes(), boxes, selected, reach, scratch,
      [&](int i) { return Range{same ? i + 1 : near_b.begin, near_b.end}; }, exclude_none, [&](int i, int j) {
        const int f = t.face_order()[i], h = t.face_order()[j];
        out.face_face.push_back({body.body, f < h ? f : h, body.body, f < h ? h : f});
      });
}

// leaf_primitives_overlapping, lanes::kFloatLanes primitives at a time.
template <class Gap>
CLOTHCD_SIMD_ENTRY int overlapping_lanes(const Bvh& bvh, int leaf, LeafPrimitives kind, const FlatBox& box,
                                         const PackedBox& packed, Gap gap, LeafScratch& scratch,
                                         std::vector<int>& out) {
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
  const int selected = select_packed(packed_boxes, range.begin, range.end, packed, scratch.selected);
  for (int k = 0; k < selected; ++k) {
    const int i = scratch.selected[k];
    if (within(boxes[i], box, gap)) out.push_back(i);
  }
  return range.end - range.begin;
}
