#pragma once
/// @file
/// Candidate pair search: descend two hierarchies (or one against itself) and test the owned primitives of overlapping
/// leaves by their swept boxes, handing the candidates to a sink in chunks as they are found. Pairs sharing a vertex
/// are skipped inside a body, and since every vertex and edge is owned by one triangle, no pair is produced twice and
/// adjacent triangles are never listed as pairs.
/// Section 3.2.1 of Jin et al.: with sphere hierarchies the root spheres are tested first, the root AABBs are built and
/// tested only when the spheres overlap, and only then does the search descend depth-first.

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

/// Search options.
struct TraversalSettings {
  bool parallel = true;  ///< Split the search into tasks run by TBB (the same pairs; the chunks' order changes).
  /// Optional restriction for re-searching after a few vertices moved: flags (non-zero = moved) for the vertices of
  /// the searched body (find_self_candidates) or of the first body (find_pair_candidates). When set, exactly the
  /// pairs of the unrestricted search that involve a moved vertex of that body are returned. With at most one vertex
  /// in kMovedQueryShare moved, the boxes of the moved primitives query the hierarchies (serially); with more, the
  /// descent skips the subtrees without a moved vertex. Must stay valid during the call; its size must be that body's
  /// vertex count.
  const std::vector<std::uint8_t>* moved_vertices = nullptr;
  /// A task passes its candidates on to the CandidateSink once it holds this many (>= 1; a chunk may exceed it by the
  /// pairs of one leaf pair).
  std::size_t chunk_pairs = 1024;
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
/// Sphere (descended on its node boxes, Bvh::boxes()); throws std::invalid_argument for Obb, and for chunk_pairs 0.
/// With `parallel`, one body's search is split into node-pair tasks that every thread takes from.
void find_self_candidates(const BodyView& body, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats = nullptr);

/// Hands to `sink`, in chunks as find_self_candidates does, every pair between body `a` and body `b` (a.body < b.body)
/// whose swept boxes overlap: vertices of a vs faces of b, vertices of b vs faces of a, edges of a vs edges of b.
/// Volume pairs: Aabb-Aabb, Sphere-Sphere (root double box logic; below the root, node spheres first and node boxes
/// when the spheres overlap), Aabb-Obb. Throws std::invalid_argument for any other combination, and for chunk_pairs 0.
void find_pair_candidates(const BodyView& a, const BodyView& b, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats = nullptr);

}  // namespace clothcd::broadphase
