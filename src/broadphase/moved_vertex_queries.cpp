// The searches restricted to a few moved vertices (moved_vertex_queries.hpp): the boxes of the moved primitives query
// the hierarchies, leaf by leaf of the moved body, instead of a descent of the hierarchies against each other.
#include "broadphase/moved_vertex_queries.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "broadphase/gap_bound.hpp"
#include "broadphase/leaf_pairs.hpp"
#include "broadphase/node_overlaps.hpp"
#include "broadphase/packed_boxes.hpp"
#include "support/simd_level.hpp"

namespace clothcd::broadphase::detail {
namespace {

// Queries of one hierarchy (the searched one) by the moved primitives of another (the moved one, possibly the same),
// leaf by leaf of the moved one: the union of a leaf's moved faces bounds all its moved primitives (a moved vertex or
// edge lies in its owning face, which moved too), so one descent with it finds every leaf of the searched hierarchy
// that a moved primitive of the leaf may touch; each moved primitive is then tested against those leaves only.
// `Reach`: the search's gap bound (gap_bound.hpp), read at each descent and at each primitive's query.
template <class Reach>
class MovedQueries {
 public:
  // The candidates go to `out`, and from there to `sink` in chunks of `chunk` pairs (see pass_on).
  MovedQueries(const Bvh& moved_tree, const Bvh& searched, const std::vector<std::uint8_t>& moved, Reach reach,
               CandidateSet& out, CandidateSink& sink, std::size_t chunk, TraversalStats& stats)
      : moved_tree_(moved_tree),
        searched_(searched),
        moved_(moved),
        reach_(reach),
        out_(out),
        sink_(sink),
        chunk_(chunk),
        stats_(stats) {
    scratch_.level = simd_level();
  }

  // True when vertex v of the moved body moved.
  bool moved(int v) const { return moved_[static_cast<std::size_t>(v)] != 0; }

  // For each leaf of the moved hierarchy with a moved face: on_vertex(i, hits), on_face(p, hits) and on_edge(i, hits)
  // for its moved vertices, faces and edges (tree positions), `hits` being the positions of the searched hierarchy's
  // faces, vertices and edges respectively whose boxes overlap the primitive's box.
  template <class OnVertex, class OnFace, class OnEdge>
  void run(const OnVertex& on_vertex, const OnFace& on_face, const OnEdge& on_edge) {
    const Bvh& t = moved_tree_;
    const int* faces = t.ordered_faces().data();
    const int* edges = t.ordered_edges().data();
    auto face_moved = [&](int p) { return moved(faces[3 * p]) || moved(faces[3 * p + 1]) || moved(faces[3 * p + 2]); };
    for (std::size_t n = 0; n < t.nodes().size(); ++n) {
      const BvhNode& leaf = t.nodes()[n];
      if (!leaf.is_leaf()) continue;
      FlatBox reach = empty_flat_box();
      for (int p = leaf.face_begin; p < leaf.face_end; ++p) {
        if (face_moved(p)) reach.expand(t.ordered_face_boxes()[p]);
      }
      if (reach.min[0] > reach.max[0]) continue;  // no moved face
      pass_on(true);
      find_leaves(reach);
      for (int i = t.vertex_offset()[leaf.face_begin]; i < t.vertex_offset()[leaf.face_end]; ++i) {
        if (moved(t.owned_vertices()[i])) {
          on_vertex(i, hits(LeafPrimitives::Faces, t.ordered_vertex_boxes()[i]));
        }
      }
      for (int p = leaf.face_begin; p < leaf.face_end; ++p) {
        if (face_moved(p)) on_face(p, hits(LeafPrimitives::Vertices, t.ordered_face_boxes()[p]));
      }
      for (int i = t.edge_offset()[leaf.face_begin]; i < t.edge_offset()[leaf.face_end]; ++i) {
        if (moved(edges[2 * i]) || moved(edges[2 * i + 1])) {
          on_edge(i, hits(LeafPrimitives::Edges, t.ordered_edge_boxes()[i]));
        }
      }
    }
    pass_on(false);
  }

 private:
  // Hands out_ to the sink and empties it, once it holds a chunk (`full_only`) or whenever it holds any.
  void pass_on(bool full_only) {
    if (out_.size() == 0 || (full_only && out_.size() < chunk_)) return;
    sink_.consume(out_);
    out_.clear();
  }

  // The leaves of the searched hierarchy whose volume overlaps `box` (is within the bound of it), into leaves_.
  void find_leaves(const FlatBox& box) {
    leaves_.clear();
    stack_.assign(1, 0);
    while (!stack_.empty()) {
      const int n = stack_.back();
      stack_.pop_back();
      ++stats_.volume_tests;
      if (!box_overlaps_node(box, searched_, n, reach_.gap())) continue;
      const BvhNode& node = searched_.nodes()[n];
      if (node.is_leaf()) {
        leaves_.push_back(n);
      } else {
        stack_.push_back(node.right);
        stack_.push_back(n + 1);
      }
    }
  }

  // Positions of the searched hierarchy's primitives of `kind` in leaves_ whose boxes overlap `box` (are within the
  // bound of it).
  const std::vector<int>& hits(LeafPrimitives kind, const FlatBox& box) {
    hits_.clear();
    const auto gap = reach_.gap();
    const PackedBox packed = packed_reach(box, pack_box(box), gap);
    for (const int leaf : leaves_) {
      // The leaf's box first, where the hierarchy keeps one: most of a group's leaves miss a single primitive.
      ++stats_.volume_tests;
      if (!searched_.boxes().empty() && !within(searched_.boxes()[leaf], box, gap)) continue;
      stats_.primitive_tests += leaf_primitives_overlapping(searched_, leaf, kind, box, packed, gap, scratch_, hits_);
    }
    return hits_;
  }

  const Bvh& moved_tree_;
  const Bvh& searched_;
  const std::vector<std::uint8_t>& moved_;
  Reach reach_;
  CandidateSet& out_;
  CandidateSink& sink_;
  std::size_t chunk_;
  TraversalStats& stats_;
  LeafScratch scratch_;
  std::vector<int> stack_;
  std::vector<int> leaves_;
  std::vector<int> hits_;
};

}  // namespace

bool few_moved(const std::vector<std::uint8_t>& moved) {
  std::size_t count = 0;
  for (const std::uint8_t m : moved) count += m != 0 ? 1 : 0;
  return count * kMovedQueryShare <= moved.size();
}

namespace {

// Each moved vertex against the faces, each moved face against the unmoved vertices, each moved edge against the
// edges (a pair of two moved edges from the one of lower index).
template <class Reach>
void query_moved_self_within(const BodyView& body, const std::vector<std::uint8_t>& moved, Reach reach,
                             std::size_t chunk_pairs, CandidateSink& sink, TraversalStats& stats) {
  const Bvh& t = *body.bvh;
  const int id = body.body;
  const int* faces = t.ordered_faces().data();
  const int* edges = t.ordered_edges().data();
  CandidateSet out;
  MovedQueries<Reach> queries(t, t, moved, reach, out, sink, chunk_pairs, stats);
  queries.run(
      [&](int i, const std::vector<int>& face_hits) {
        const int v = t.owned_vertices()[i];
        for (const int p : face_hits) {
          const int* f = faces + 3 * p;
          if (f[0] != v && f[1] != v && f[2] != v) out.vertex_face.push_back({id, v, id, t.face_order()[p]});
        }
      },
      [&](int p, const std::vector<int>& vertex_hits) {
        const int* f = faces + 3 * p;
        for (const int i : vertex_hits) {
          const int v = t.owned_vertices()[i];
          if (!queries.moved(v) && f[0] != v && f[1] != v && f[2] != v) {
            out.vertex_face.push_back({id, v, id, t.face_order()[p]});
          }
        }
      },
      [&](int i, const std::vector<int>& edge_hits) {
        const int a0 = edges[2 * i], a1 = edges[2 * i + 1];
        const int e = t.owned_edges()[i];
        for (const int j : edge_hits) {
          const int b0 = edges[2 * j], b1 = edges[2 * j + 1];
          if (b0 == a0 || b0 == a1 || b1 == a0 || b1 == a1) continue;  // shares a vertex (or is the same edge)
          const int g = t.owned_edges()[j];
          if ((queries.moved(b0) || queries.moved(b1)) && g < e) continue;  // found from g
          out.edge_edge.push_back({id, e < g ? e : g, id, e < g ? g : e});
        }
      });
}

// Each moved vertex of a against b's faces, each moved face of a against b's vertices, each moved edge of a against
// b's edges.
template <class Reach>
void query_moved_pair_within(const BodyView& a, const BodyView& b, const std::vector<std::uint8_t>& moved, Reach reach,
                             std::size_t chunk_pairs, CandidateSink& sink, TraversalStats& stats) {
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  CandidateSet out;
  MovedQueries<Reach> queries(ta, tb, moved, reach, out, sink, chunk_pairs, stats);
  queries.run(
      [&](int i, const std::vector<int>& face_hits) {
        for (const int p : face_hits) {
          out.vertex_face.push_back({a.body, ta.owned_vertices()[i], b.body, tb.face_order()[p]});
        }
      },
      [&](int p, const std::vector<int>& vertex_hits) {
        for (const int i : vertex_hits) {
          out.vertex_face.push_back({b.body, tb.owned_vertices()[i], a.body, ta.face_order()[p]});
        }
      },
      [&](int i, const std::vector<int>& edge_hits) {
        for (const int j : edge_hits) {
          out.edge_edge.push_back({a.body, ta.owned_edges()[i], b.body, tb.owned_edges()[j]});
        }
      });
}

}  // namespace

void query_moved_self(const BodyView& body, const std::vector<std::uint8_t>& moved,
                      const std::atomic<double>* gap_bound, std::size_t chunk_pairs, CandidateSink& sink,
                      TraversalStats& stats) {
  if (gap_bound == nullptr) {
    query_moved_self_within(body, moved, Touching{}, chunk_pairs, sink, stats);
  } else {
    query_moved_self_within(body, moved, WithinBound{gap_bound}, chunk_pairs, sink, stats);
  }
}

void query_moved_pair(const BodyView& a, const BodyView& b, const std::vector<std::uint8_t>& moved,
                      const std::atomic<double>* gap_bound, std::size_t chunk_pairs, CandidateSink& sink,
                      TraversalStats& stats) {
  if (gap_bound == nullptr) {
    query_moved_pair_within(a, b, moved, Touching{}, chunk_pairs, sink, stats);
  } else {
    query_moved_pair_within(a, b, moved, WithinBound{gap_bound}, chunk_pairs, sink, stats);
  }
}

}  // namespace clothcd::broadphase::detail
