// Refitting a body's bounding volume hierarchy (bvh.hpp) to each step's swept boxes: the primitive boxes in tree
// order and the AABB, sphere or OBB node volumes bottom-up (all of them, or only those holding a moved vertex), and a
// rebuild when the refitted tree has grown too loose. Sphere nodes follow Jin et al., section 3.2.1 (bounding spheres
// for non-root nodes); the root's second volume, its AABB, is built by the search only when the root spheres overlap
// (traversal.cpp).
#include "broadphase/bvh.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_invoke.h>

namespace clothcd::broadphase {
namespace {

// Relative padding that keeps rounding from shrinking a sphere or OBB below what it must contain.
constexpr double kPad = 1e-12;

double box_area(const FlatBox& b) {
  const double dx = b.max[0] - b.min[0], dy = b.max[1] - b.min[1], dz = b.max[2] - b.min[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

geometry::Sphere box_sphere(const FlatBox& b) {
  geometry::Sphere s;
  Eigen::Vector3d half;
  for (int k = 0; k < 3; ++k) {
    s.center[k] = 0.5 * (b.min[k] + b.max[k]);
    half[k] = 0.5 * (b.max[k] - b.min[k]);
  }
  s.radius = half.norm() * (1.0 + kPad);
  return s;
}

// The smallest sphere containing spheres a and b.
geometry::Sphere merge_spheres(const geometry::Sphere& a, const geometry::Sphere& b) {
  const Eigen::Vector3d d = b.center - a.center;
  const double distance = d.norm();
  if (distance + b.radius <= a.radius) return a;
  if (distance + a.radius <= b.radius) return b;
  geometry::Sphere s;
  s.radius = 0.5 * (distance + a.radius + b.radius);
  s.center = a.center + d * ((s.radius - a.radius) / distance);
  s.radius *= 1.0 + kPad;
  return s;
}

// Bodies of at least this many triangles fill their boxes in tree order on parallel tasks in refit(): below it the
// tasks cost about what they save.
constexpr int kParallelRefitFaces = 1 << 15;

}  // namespace

BvhUpdate Bvh::update(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start,
                      const Vertices& end) {
  if (nodes_.empty() || static_cast<int>(face_order_.size()) != topology.face_count()) {
    build(topology, boxes, start, end);
    return BvhUpdate::Rebuilt;
  }
  check_vertex_boxes(topology, boxes);
  refit(boxes);
  return rebuild_if_degraded(topology, boxes, start, end);
}

BvhUpdate Bvh::update_moved(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start,
                            const Vertices& end, const std::vector<std::uint8_t>& moved) {
  if (nodes_.empty() || static_cast<int>(face_order_.size()) != topology.face_count() ||
      settings_.volume == VolumeKind::Obb) {
    return update(topology, boxes, start, end);
  }
  check_vertex_boxes(topology, boxes);
  if (moved.size() != boxes.vertices.size()) {
    throw std::invalid_argument("Bvh: " + std::to_string(moved.size()) + " moved flags for " +
                                std::to_string(boxes.vertices.size()) + " vertices");
  }
  refit_moved(boxes, moved);
  return rebuild_if_degraded(topology, boxes, start, end);
}

BvhUpdate Bvh::rebuild_if_degraded(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start,
                                   const Vertices& end) {
  const bool degraded = built_looseness_ > 0 ? looseness_ > settings_.rebuild_ratio * built_looseness_
                                             : settings_.rebuild_ratio <= 0;
  if (degraded) {
    build(topology, boxes, start, end);
    return BvhUpdate::Rebuilt;
  }
  return BvhUpdate::Refitted;
}

// Edge and face boxes are unions of vertex boxes (as compute_swept_boxes makes them), so they are made here from the
// vertex boxes, straight in tree order.
void Bvh::refit(const SweptBoxes& boxes, bool first_fill_parallel) {
  const FlatBox* vertex_boxes = boxes.vertices.data();
  const auto face_boxes = [&] {
    ordered_face_boxes_.resize(face_order_.size());
    for (std::size_t p = 0; p < face_order_.size(); ++p) {
      const int* f = ordered_faces_.data() + 3 * p;
      FlatBox b = vertex_boxes[f[0]];
      b.expand(vertex_boxes[f[1]]);
      b.expand(vertex_boxes[f[2]]);
      ordered_face_boxes_[p] = b;
    }
    packed_face_boxes_.assign(ordered_face_boxes_);
  };
  const auto vertex_boxes_in_order = [&] {
    ordered_vertex_boxes_.resize(owned_vertices_.size());
    for (std::size_t i = 0; i < owned_vertices_.size(); ++i) {
      ordered_vertex_boxes_[i] = vertex_boxes[owned_vertices_[i]];
    }
    packed_vertex_boxes_.assign(ordered_vertex_boxes_);
  };
  const auto edge_boxes = [&] {
    ordered_edge_boxes_.resize(owned_edges_.size());
    for (std::size_t i = 0; i < owned_edges_.size(); ++i) {
      FlatBox b = vertex_boxes[ordered_edges_[2 * i]];
      b.expand(vertex_boxes[ordered_edges_[2 * i + 1]]);
      ordered_edge_boxes_[i] = b;
    }
    packed_edge_boxes_.assign(ordered_edge_boxes_);
  };
  // The three kinds are independent: large bodies fill them on parallel tasks, and so does a build's first fill of
  // a body too small for that (its arrays are fresh memory, whose first touch costs more than the fill).
  if (first_fill_parallel || (settings_.parallel && static_cast<int>(face_order_.size()) >= kParallelRefitFaces)) {
    tbb::parallel_invoke(face_boxes, vertex_boxes_in_order, edge_boxes);
  } else {
    face_boxes();
    vertex_boxes_in_order();
    edge_boxes();
  }
  const int node_count = static_cast<int>(nodes_.size());
  looseness_ = 0.0;
  if (settings_.volume == VolumeKind::Obb) {
    packed_node_boxes_.assign({});
    obbs_.resize(node_count);
    for (int i = 0; i < node_count; ++i) {
      geometry::Obb& obb = obbs_[i];
      const Eigen::Matrix3d axes_t = obb.axes.transpose();
      const Eigen::Matrix3d abs_axes_t = axes_t.cwiseAbs();
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
      Eigen::Vector3d hi = -lo;
      for (int p = nodes_[i].face_begin; p < nodes_[i].face_end; ++p) {
        const FlatBox& b = ordered_face_boxes_[p];
        const Eigen::Vector3d c(0.5 * (b.min[0] + b.max[0]), 0.5 * (b.min[1] + b.max[1]), 0.5 * (b.min[2] + b.max[2]));
        const Eigen::Vector3d h(0.5 * (b.max[0] - b.min[0]), 0.5 * (b.max[1] - b.min[1]), 0.5 * (b.max[2] - b.min[2]));
        const Eigen::Vector3d center = axes_t * c;
        const Eigen::Vector3d radius = abs_axes_t * h;
        lo = lo.cwiseMin(center - radius);
        hi = hi.cwiseMax(center + radius);
      }
      const double scale = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
      obb.center = obb.axes * (0.5 * (lo + hi));
      obb.half_extents = (0.5 * (hi - lo)).array() + kPad * scale;
      if (!nodes_[i].is_leaf()) {
        const Eigen::Vector3d& e = obb.half_extents;
        looseness_ += 8.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
      }
    }
    return;
  }
  // Sphere hierarchies keep their node boxes too: the self-collision search descends on them (see traversal.cpp).
  boxes_.resize(node_count);
  if (settings_.volume == VolumeKind::Sphere) spheres_.resize(node_count);
  for (int i = node_count - 1; i >= 0; --i) fit_node(i);
  sum_looseness();
  packed_node_boxes_.assign(boxes_);
}

void Bvh::refit_moved(const SweptBoxes& boxes, const std::vector<std::uint8_t>& moved) {
  const FlatBox* vertex_boxes = boxes.vertices.data();
  const int node_count = static_cast<int>(nodes_.size());
  std::vector<std::uint8_t> changed(static_cast<std::size_t>(node_count), 0);
  for (int i = node_count - 1; i >= 0; --i) {  // children follow their parent
    const BvhNode& node = nodes_[i];
    if (!node.is_leaf()) {
      if (!(changed[i + 1] | changed[node.right])) continue;
    } else {
      bool touched = false;
      for (int p = 3 * node.face_begin; p < 3 * node.face_end && !touched; ++p) touched = moved[ordered_faces_[p]] != 0;
      if (!touched) continue;
      // The leaf's primitives with a moved vertex, as refit() derives them (its faces hold every vertex and edge it
      // owns); the others keep their boxes, which only their own vertices' boxes determine.
      auto is_moved = [&moved](int v) { return moved[static_cast<std::size_t>(v)] != 0; };
      for (int p = node.face_begin; p < node.face_end; ++p) {
        const int* f = ordered_faces_.data() + 3 * p;
        if (!is_moved(f[0]) && !is_moved(f[1]) && !is_moved(f[2])) continue;
        FlatBox b = vertex_boxes[f[0]];
        b.expand(vertex_boxes[f[1]]);
        b.expand(vertex_boxes[f[2]]);
        ordered_face_boxes_[p] = b;
        packed_face_boxes_.set(p, b);
      }
      for (int v = vertex_offset_[node.face_begin]; v < vertex_offset_[node.face_end]; ++v) {
        if (!is_moved(owned_vertices_[v])) continue;
        ordered_vertex_boxes_[v] = vertex_boxes[owned_vertices_[v]];
        packed_vertex_boxes_.set(v, ordered_vertex_boxes_[v]);
      }
      for (int e = edge_offset_[node.face_begin]; e < edge_offset_[node.face_end]; ++e) {
        if (!is_moved(ordered_edges_[2 * e]) && !is_moved(ordered_edges_[2 * e + 1])) continue;
        FlatBox b = vertex_boxes[ordered_edges_[2 * e]];
        b.expand(vertex_boxes[ordered_edges_[2 * e + 1]]);
        ordered_edge_boxes_[e] = b;
        packed_edge_boxes_.set(e, b);
      }
    }
    changed[i] = 1;
    fit_node(i);
    packed_node_boxes_.set(i, boxes_[i]);
  }
  sum_looseness();
}

void Bvh::fit_node(int i) {
  const BvhNode& node = nodes_[i];
  FlatBox b = empty_flat_box();
  if (node.is_leaf()) {
    for (int p = node.face_begin; p < node.face_end; ++p) b.expand(ordered_face_boxes_[p]);
  } else {
    b = boxes_[i + 1];
    b.expand(boxes_[node.right]);
  }
  boxes_[i] = b;
  if (settings_.volume != VolumeKind::Sphere) return;
  spheres_[i] = node.is_leaf() ? box_sphere(b) : merge_spheres(spheres_[i + 1], spheres_[node.right]);
}

void Bvh::sum_looseness() {
  looseness_ = 0.0;
  for (int i = static_cast<int>(nodes_.size()) - 1; i >= 0; --i) {  // the order refit() has always summed in
    if (nodes_[i].is_leaf()) continue;
    looseness_ += settings_.volume == VolumeKind::Sphere ? 4.0 * spheres_[i].radius * spheres_[i].radius
                                                         : box_area(boxes_[i]);
  }
}

}  // namespace clothcd::broadphase
