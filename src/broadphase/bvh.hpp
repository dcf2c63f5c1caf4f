#pragma once
/// @file
/// A bounding volume hierarchy over the triangles of one body, with AABB, sphere or OBB nodes, built top-down once and
/// refitted bottom-up every step; it is rebuilt when refitting has made it much looser than when it was built (the
/// build in bvh_build.cpp, the refit and the rebuild rule in bvh_refit.cpp).

#include <cstdint>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/packed_boxes.hpp"
#include "broadphase/swept_boxes.hpp"
#include "clothcd/geometry/bounding_volumes.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::broadphase {

/// The bounding volume stored in every node of a hierarchy.
enum class VolumeKind {
  Aabb,    ///< Axis-aligned boxes.
  Sphere,  ///< Spheres (the root can also carry an AABB, built on demand: the paper's root-node double box).
  Obb,     ///< Oriented boxes (axes from the node's vertices, extents bounding its swept triangle boxes).
};

/// How a hierarchy is built and when it is rebuilt.
struct BvhSettings {
  VolumeKind volume = VolumeKind::Aabb;  ///< Node volume.
  int max_leaf_faces = 2;                ///< A node with at most this many triangles is a leaf (>= 1).
  /// Rebuild rule: after a refit, the hierarchy is rebuilt from scratch when its looseness (the sum over internal nodes
  /// of the box surface area, or of 4 r^2 for spheres) exceeds `rebuild_ratio` times its value right after the last
  /// build. 0 rebuilds every step; infinity never rebuilds.
  double rebuild_ratio = 2.0;
  /// Build the subtrees of large hierarchies on TBB threads (the tree is the same either way).
  bool parallel = true;
};

/// One node: its triangles are face_order[face_begin, face_end); the left child is the next node, the right child is
/// node `right` (-1 for a leaf). Nodes are stored in depth-first pre-order, so children follow their parent.
struct BvhNode {
  int right = -1;      ///< Index of the right child, -1 for a leaf.
  int face_begin = 0;  ///< First position in face_order.
  int face_end = 0;    ///< One past the last position in face_order.

  /// True for a leaf.
  [[nodiscard]] bool is_leaf() const { return right < 0; }
};

/// What update() did.
enum class BvhUpdate {
  Refitted,  ///< Volumes recomputed bottom-up with the same tree.
  Rebuilt,   ///< The tree was rebuilt because the rebuild rule fired (or it had never been built).
};

/// Hierarchy over one body's triangles. Owned vertices and edges (BodyTopology owners) are stored in the order of their
/// owning triangle, so every node, leaf or not, holds a contiguous range of them.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class Bvh {
 public:
  /// An empty hierarchy with the given settings; call build() or update() before use.
  explicit Bvh(const BvhSettings& settings = {});

  /// Builds the tree top-down (triangle box centres split by the binned surface-area heuristic, the median along the
  /// widest axis where they cannot be) and its volumes.
  /// `start`/`end` are the body's positions (#V x 3), used for OBB axes; `boxes` must match them. Only
  /// `boxes.vertices` is read (edge and face boxes are their unions; compute_swept_vertex_boxes is enough);
  /// std::invalid_argument when it does not hold one box per vertex or a face's box is not finite.
  void build(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start, const Vertices& end);

  /// Refits the volumes bottom-up for new boxes and positions, then rebuilds if the rebuild rule fires. Reads
  /// `boxes` as build() does.
  BvhUpdate update(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start, const Vertices& end);

  /// update() when only the vertices flagged in `moved` (one flag per vertex of the body) may have changed their boxes
  /// since the last build or update: recomputes only the boxes and volumes that contain such a vertex, and gives the
  /// same hierarchy as update(), bit for bit. OBB hierarchies, and one not built for this topology, take update().
  BvhUpdate update_moved(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start,
                         const Vertices& end, const std::vector<std::uint8_t>& moved);

  /// Settings in use.
  [[nodiscard]] const BvhSettings& settings() const { return settings_; }
  /// Nodes in pre-order; node 0 is the root. Empty before the first build.
  [[nodiscard]] const std::vector<BvhNode>& nodes() const { return nodes_; }
  /// #F face indices in tree order.
  [[nodiscard]] const std::vector<int>& face_order() const { return face_order_; }
  /// Owned vertices in tree order; those of node n are owned_vertices[vertex_offset[n.face_begin] .. [n.face_end]).
  [[nodiscard]] const std::vector<int>& owned_vertices() const { return owned_vertices_; }
  /// #F + 1 prefix offsets into owned_vertices, indexed by position in face_order.
  [[nodiscard]] const std::vector<int>& vertex_offset() const { return vertex_offset_; }
  /// Owned edges in tree order, indexed like owned_vertices through edge_offset.
  [[nodiscard]] const std::vector<int>& owned_edges() const { return owned_edges_; }
  /// #F + 1 prefix offsets into owned_edges.
  [[nodiscard]] const std::vector<int>& edge_offset() const { return edge_offset_; }
  /// The swept boxes of the last build/update copied into tree order, so that the leaves' primitive tests read
  /// contiguous memory: faces by position in face_order, vertices and edges by position in owned_vertices/owned_edges.
  [[nodiscard]] const std::vector<FlatBox>& ordered_face_boxes() const { return ordered_face_boxes_; }
  /// Vertex boxes in owned_vertices order (see ordered_face_boxes).
  [[nodiscard]] const std::vector<FlatBox>& ordered_vertex_boxes() const { return ordered_vertex_boxes_; }
  /// Edge boxes in owned_edges order (see ordered_face_boxes).
  [[nodiscard]] const std::vector<FlatBox>& ordered_edge_boxes() const { return ordered_edge_boxes_; }
  /// Outward-rounded single-precision copies of ordered_face_boxes, for four-at-a-time pre-selection.
  [[nodiscard]] const PackedBoxes& packed_face_boxes() const { return packed_face_boxes_; }
  /// Outward-rounded single-precision copies of ordered_vertex_boxes.
  [[nodiscard]] const PackedBoxes& packed_vertex_boxes() const { return packed_vertex_boxes_; }
  /// Outward-rounded single-precision copies of ordered_edge_boxes.
  [[nodiscard]] const PackedBoxes& packed_edge_boxes() const { return packed_edge_boxes_; }
  /// Outward-rounded single-precision copies of the node boxes (empty with the node boxes, for VolumeKind::Obb).
  [[nodiscard]] const PackedBoxes& packed_node_boxes() const { return packed_node_boxes_; }
  /// ordered_faces as three rows (four-at-a-time shared-vertex tests).
  [[nodiscard]] const PackedVertexIds& packed_faces() const { return packed_faces_; }
  /// ordered_edges as two rows.
  [[nodiscard]] const PackedVertexIds& packed_edges() const { return packed_edges_; }
  /// The three vertices of each face in face_order order (3 ints per position).
  [[nodiscard]] const std::vector<int>& ordered_faces() const { return ordered_faces_; }
  /// The two vertices of each edge in owned_edges order (2 ints per position).
  [[nodiscard]] const std::vector<int>& ordered_edges() const { return ordered_edges_; }
  /// Node boxes, one per node: the volumes of VolumeKind::Aabb; sphere hierarchies keep them as well (the
  /// self-collision search descends on them); empty for VolumeKind::Obb.
  [[nodiscard]] const std::vector<FlatBox>& boxes() const { return boxes_; }
  /// Node spheres (VolumeKind::Sphere), one per node.
  [[nodiscard]] const std::vector<geometry::Sphere>& spheres() const { return spheres_; }
  /// Node oriented boxes (VolumeKind::Obb), one per node.
  [[nodiscard]] const std::vector<geometry::Obb>& obbs() const { return obbs_; }
  /// Looseness (see BvhSettings::rebuild_ratio) now and right after the last build.
  [[nodiscard]] double looseness() const { return looseness_; }
  /// Looseness right after the last build.
  [[nodiscard]] double built_looseness() const { return built_looseness_; }
  /// Number of builds so far (the first one included).
  [[nodiscard]] int build_count() const { return build_count_; }

 private:
  static void check_vertex_boxes(const BodyTopology& topology, const SweptBoxes& boxes);
  // Recomputes every volume from `boxes` in the current tree; `first_fill_parallel`: fill the primitive boxes on
  // parallel tasks whatever the body's size (a build's first fill).
  void refit(const SweptBoxes& boxes, bool first_fill_parallel = false);
  void refit_moved(const SweptBoxes& boxes, const std::vector<std::uint8_t>& moved);
  void fit_node(int i);
  void sum_looseness();
  BvhUpdate rebuild_if_degraded(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start,
                                const Vertices& end);
  void fit_obb_axes(const BodyTopology& topology, const Vertices& start, const Vertices& end);

  BvhSettings settings_;
  std::vector<BvhNode> nodes_;
  std::vector<int> face_order_;
  std::vector<int> owned_vertices_;
  std::vector<int> vertex_offset_;
  std::vector<int> owned_edges_;
  std::vector<int> edge_offset_;
  std::vector<FlatBox> boxes_;
  std::vector<geometry::Sphere> spheres_;
  std::vector<geometry::Obb> obbs_;
  std::vector<FlatBox> ordered_face_boxes_;
  std::vector<FlatBox> ordered_vertex_boxes_;
  std::vector<FlatBox> ordered_edge_boxes_;
  PackedBoxes packed_face_boxes_;
  PackedBoxes packed_vertex_boxes_;
  PackedBoxes packed_edge_boxes_;
  PackedBoxes packed_node_boxes_;
  std::vector<int> ordered_faces_;
  PackedVertexIds packed_faces_;
  PackedVertexIds packed_edges_;
  std::vector<int> ordered_edges_;
  double looseness_ = 0.0;
  double built_looseness_ = 0.0;
  int build_count_ = 0;
};

}  // namespace clothcd::broadphase
