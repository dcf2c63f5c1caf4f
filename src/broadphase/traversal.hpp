#pragma once
/// @file
/// Candidate pair search: descend two hierarchies (or one against itself) and test the owned primitives of overlapping
/// leaves by their swept boxes, handing the candidates to a sink in chunks as they are found. Pairs sharing a vertex
/// are skipped inside a body, and since every vertex and edge is owned by one triangle, no pair is produced twice and
/// adjacent triangles are never listed as pairs. The search can instead list face pairs (SearchedPairs::FaceFace, for
/// the intersecting faces of one state), and can take a gap bound that it reads as it goes (for the pairs within a
/// distance and the minimum distance: branch and bound).
/// Section 3.2.1 of Jin et al.: with sphere hierarchies the root spheres are tested first, the root AABBs are built and
/// tested only when the spheres overlap, and only then does the search descend depth-first.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/swept_boxes.hpp"

namespace clothcd::broadphase {

/// One body as the search sees it; every pointer must stay valid during the call.
struct BodyView {
  int body = 0;                            ///< Body id written into the candidates (0 = cloth).
  const BodyTopology* topology = nullptr;  ///< Primitives and owners.
  const SweptBoxes* boxes = nullptr;       ///< Swept boxes of the step.
  const Bvh* bvh = nullptr;                ///< Hierarchy refitted to `boxes` (unused by the brute-force reference).
};

/// A search restricted to moved vertices queries the hierarchies primitive by primitive when at most one vertex in
/// this many moved (see TraversalSettings::moved_vertices).
constexpr std::size_t kMovedQueryShare = 16;

/// Which primitive pairs a search produces.
enum class SearchedPairs {
  /// Vertex-face and edge-edge pairs (CandidateSet::vertex_face and edge_edge), those sharing a vertex skipped inside
  /// a body: the pairs of the contact queries.
  VertexFaceEdgeEdge,
  /// Face pairs (CandidateSet::face_face): every pair of faces whose boxes overlap, inside a body those sharing
  /// vertices too (faces meeting at a vertex or an edge may intersect beyond it), never a face with itself.
  FaceFace,
};

/// Search options.
struct TraversalSettings {
  bool parallel = true;  ///< Split the search into tasks run by TBB (the same pairs; the chunks' order changes).
  /// Optional restriction for re-searching after a few vertices moved: flags (non-zero = moved) for the vertices of
  /// the searched body (find_self_candidates) or of the first body (find_pair_candidates). When set, exactly the
  /// pairs of the unrestricted search that involve a moved vertex of that body are returned. With at most one vertex
  /// in kMovedQueryShare moved, the boxes of the moved primitives query the hierarchies (serially); with more, the
  /// descent skips the subtrees without a moved vertex. Must stay valid during the call; its size must be that body's
  /// vertex count. Not with SearchedPairs::FaceFace (std::invalid_argument).
  const std::vector<std::uint8_t>* moved_vertices = nullptr;
  /// A task passes its candidates on to the CandidateSink once it holds this many (>= 1; a chunk may exceed it by the
  /// pairs of one leaf pair).
  std::size_t chunk_pairs = 1024;
  /// The pairs to produce.
  SearchedPairs pairs = SearchedPairs::VertexFaceEdgeEdge;
  /// Optional gap bound, for branch and bound (the minimum distance: a sink lowers it to the smallest distance found
  /// so far, on boxes refitted without inflation) and for pairs within a distance. When set, every overlap test of
  /// the search (node volumes, the root double box, primitive boxes against leaf boxes and against each other) passes
  /// for volumes within its current value of each other along every axis (spheres: with their radius grown by
  /// sqrt(3) times it, which holds every point that close), so the search produces the pairs whose primitive boxes
  /// are within it along every axis (each per-axis difference of their bounds, rounded, at most the value). The value
  /// is read (memory_order_relaxed) at each node test and for each primitive's tests, so a sink (or any thread) that
  /// lowers it while the search runs prunes the rest of the search, and the descent visits the nearer of two child
  /// pairs first. It must be >= 0 (+infinity: every pair; std::invalid_argument for a negative or NaN value at the
  /// start) and may only be lowered during the search: every pair within its final value is produced, and pairs within
  /// an earlier value may be too. 0 produces the pairs of the search without a bound. Must stay valid during the call.
  const std::atomic<double>* gap_bound = nullptr;
};

/// Receives the candidates of a search chunk by chunk, so that the candidates of a step are never all held at once
/// (see find_self_candidates and find_pair_candidates; collecting_sink.hpp collects them into one set).
class CandidateSink {
 public:
  virtual ~CandidateSink() = default;
  /// Takes one chunk of candidates (the search clears it after the call). Called from the search's threads, possibly
  /// from several at once, each call with its own chunk; chunks come in no particular order.
  virtual void consume(const CandidateSet& chunk) = 0;
};

/// What one search did.
struct TraversalStats {
  long volume_tests = 0;             ///< Node volume overlap tests.
  long primitive_tests = 0;          ///< Primitive swept-box tests.
  bool root_sphere_overlap = false;  ///< Sphere hierarchies: the root spheres overlapped.
  bool root_aabb_overlap = false;    ///< Sphere hierarchies: the root AABBs were built and overlapped.
  /// Time of the search summed over its tasks, the sink's work included (on one thread: the wall time).
  double task_ms = 0.0;

  /// Adds the counts of `o` (flags are or-ed).
  void add(const TraversalStats& o) {
    volume_tests += o.volume_tests;
    primitive_tests += o.primitive_tests;
    root_sphere_overlap = root_sphere_overlap || o.root_sphere_overlap;
    root_aabb_overlap = root_aabb_overlap || o.root_aabb_overlap;
    task_ms += o.task_ms;
  }
};

/// The AABB of a whole body for the step (union of its vertex boxes): the second root volume of the double box.
[[nodiscard]] FlatBox body_box(const BodyView& body);

/// Hands to `sink`, in chunks (TraversalSettings::chunk_pairs) as the search finds them, every vertex-face pair (v, f)
/// with v not in f and every edge-edge pair sharing no vertex, within `body`, whose swept boxes overlap: each pair
/// once, in no particular order (see sort_candidates), and no storage proportional to them. Node volumes: Aabb, or
/// Sphere (descended on its node boxes, Bvh::boxes()); throws std::invalid_argument for Obb, for chunk_pairs 0, and
/// for moved_vertices with SearchedPairs::FaceFace. With SearchedPairs::FaceFace: every pair of faces whose boxes
/// overlap instead (face_a < face_b). With a gap_bound: the pairs within it instead of overlapping.
/// With `parallel`, one body's search is split into node-pair tasks that every thread takes from.
void find_self_candidates(const BodyView& body, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats = nullptr);

/// Hands to `sink`, in chunks as find_self_candidates does, every pair between body `a` and body `b` (a.body < b.body)
/// whose swept boxes overlap: vertices of a vs faces of b, vertices of b vs faces of a, edges of a vs edges of b.
/// Volume pairs: Aabb-Aabb, Sphere-Sphere (root double box logic; below the root, node spheres first and node boxes
/// when the spheres overlap), Aabb-Obb. Throws std::invalid_argument for any other combination, and as
/// find_self_candidates does. With SearchedPairs::FaceFace: every face of a against every face of b whose boxes
/// overlap instead; with a gap_bound, those within it.
void find_pair_candidates(const BodyView& a, const BodyView& b, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats = nullptr);

}  // namespace clothcd::broadphase
