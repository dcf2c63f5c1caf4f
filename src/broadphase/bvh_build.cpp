// Building a body's bounding volume hierarchy (bvh.hpp): a top-down split of the triangles by the binned surface-area
// heuristic (the median on the longest axis when the centroids cannot be split), large ranges split on TBB tasks into
// the same tree, then the vertices, edges and faces in tree order and each node's OBB axes; the volumes come from the
// first refit (bvh_refit.cpp).
#include "broadphase/bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "broadphase/node_obb_axes.hpp"
#include "support/simd.hpp"

namespace clothcd::broadphase {
namespace {

constexpr float kFloatInfinity = std::numeric_limits<float>::infinity();

// A triangle during the build, in single precision (the splits only choose where to cut; the node volumes are
// refitted from the double-precision boxes): its box, its box's centre (times two) and its index, kept in tree order
// so that the splits read memory in sequence. The box is stored as its low corner and its negated high corner, so
// that the union of two boxes is a lane-wise minimum of two vector pairs.
struct BuildItem {
  // Left uninitialised (not zeroed by std::vector): the build's parallel fill then touches the fresh pages first.
  BuildItem() {}  // NOLINT(modernize-use-equals-default): `= default` would let value-initialisation zero it
  simd::F32x4 low;             // lo x, y, z, 0
  simd::F32x4 negated_high;    // -hi x, y, z, 0
  float centroid[3];
  int face;
};

// A box of build items (single precision), in BuildItem's layout.
struct ItemBox {
  simd::F32x4 low = simd::F32x4{} + kFloatInfinity;
  simd::F32x4 negated_high = simd::F32x4{} + kFloatInfinity;

  void expand(simd::F32x4 other_low, simd::F32x4 other_negated_high) {
    low = other_low < low ? other_low : low;
    negated_high = other_negated_high < negated_high ? other_negated_high : negated_high;
  }
  void expand(const ItemBox& o) { expand(o.low, o.negated_high); }
  [[nodiscard]] float lo(int axis) const { return low[axis]; }
  [[nodiscard]] float hi(int axis) const { return -negated_high[axis]; }
  // Half the surface area (in double: the costs compare sums of many areas).
  [[nodiscard]] double half_area() const {
    const double dx = double{hi(0)} - lo(0), dy = double{hi(1)} - lo(1), dz = double{hi(2)} - lo(2);
    return dx * dy + dy * dz + dz * dx;
  }
};

struct BuildContext {
  std::vector<BuildItem>& items;
  int max_leaf;
};

constexpr int kSahBins = 16;

// The bin of centroid coordinate x for bins of width 1 / scale from lo: 0 .. kSahBins - 1 (0 for NaN, the last for
// infinity).
int bin_of(float x, float lo, float scale) {
  const float b = (x - lo) * scale;
  const float clamped = b > 0.0f ? (b < kSahBins - 1 ? b : kSahBins - 1) : 0.0f;  // without branches
  return static_cast<int>(clamped);
}

// Where to split items[begin, end): the binned surface-area heuristic over the centroid bounds (the split that
// minimises area(left) * count(left) + area(right) * count(right)), falling back to the median on the longest axis
// when every centroid falls in one bin. Reorders the range so that [begin, middle) is the left child; returns middle.
int split_range(BuildContext& context, int begin, int end) {
  ItemBox bounds;
  const auto first = context.items.begin() + begin, last = context.items.begin() + end;
  for (auto item = first; item != last; ++item) {
    const simd::F32x4 c{item->centroid[0], item->centroid[1], item->centroid[2], 0.0f};
    bounds.expand(c, -c);
  }
  const std::array<float, 3> lo{bounds.lo(0), bounds.lo(1), bounds.lo(2)};
  const std::array<float, 3> hi{bounds.hi(0), bounds.hi(1), bounds.hi(2)};
  // Only an axis of finite, non-zero extent and scale is split by its bins (a zero, subnormal or infinite extent makes
  // every bin index of the axis 0 or the last, bin_of clamping NaN and infinities, and the axis is skipped).
  std::array<float, 3> scale{};
  std::array<bool, 3> binned{};
  for (int axis = 0; axis < 3; ++axis) {
    const float extent = hi[axis] - lo[axis];
    scale[axis] = kSahBins / extent;
    binned[axis] = extent > 0.0f && std::isfinite(extent) && std::isfinite(scale[axis]);
  }
  // One pass over the triangles fills the bins of all three axes.
  std::array<std::array<ItemBox, kSahBins>, 3> bin_box;
  std::array<std::array<int, kSahBins>, 3> bin_count{};
  for (auto item = first; item != last; ++item) {
    for (int axis = 0; axis < 3; ++axis) {
      const int bin = bin_of(item->centroid[axis], lo[axis], scale[axis]);
      bin_box[axis][bin].expand(item->low, item->negated_high);
      ++bin_count[axis][bin];
    }
  }
  double best_cost = std::numeric_limits<double>::infinity();
  int best_axis = -1, best_bin = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!binned[axis]) continue;
    std::array<double, kSahBins> right_cost{};
    ItemBox right;
    int right_count = 0;
    for (int b = kSahBins - 1; b > 0; --b) {
      right.expand(bin_box[axis][b]);
      right_count += bin_count[axis][b];
      right_cost[b] = right_count > 0 ? right.half_area() * right_count : 0.0;
    }
    ItemBox left;
    int left_count = 0;
    for (int b = 0; b + 1 < kSahBins; ++b) {
      left.expand(bin_box[axis][b]);
      left_count += bin_count[axis][b];
      if (left_count == 0 || left_count == end - begin) continue;
      const double cost = left.half_area() * left_count + right_cost[b + 1];
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_bin = b;
      }
    }
  }
  if (best_axis < 0) {
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    }
    const int middle = begin + (end - begin) / 2;
    std::nth_element(first, context.items.begin() + middle, last,
                     [&](const BuildItem& a, const BuildItem& b) { return a.centroid[axis] < b.centroid[axis]; });
    return middle;
  }
  const auto middle = std::partition(first, last, [&](const BuildItem& item) {
    return bin_of(item.centroid[best_axis], lo[best_axis], scale[best_axis]) <= best_bin;
  });
  return static_cast<int>(middle - context.items.begin());
}

// Appends the subtree over order[begin, end) to `nodes` in pre-order (child indices relative to the vector).
void build_range(BuildContext& context, int begin, int end, std::vector<BvhNode>& nodes) {
  const int index = static_cast<int>(nodes.size());
  nodes.push_back(BvhNode{-1, begin, end});
  if (end - begin <= context.max_leaf) return;
  const int middle = split_range(context, begin, end);
  build_range(context, begin, middle, nodes);
  nodes[static_cast<std::size_t>(index)].right = static_cast<int>(nodes.size());
  build_range(context, middle, end, nodes);
}

// Ranges of at least this many triangles build their two children as parallel tasks.
constexpr int kParallelBuildFaces = 4096;

// build_range with the children of large ranges built on TBB tasks into vectors of their own, then joined in
// pre-order: the same tree as build_range (each range is split the same way whichever thread splits it).
void build_range_parallel(BuildContext& context, int begin, int end, std::vector<BvhNode>& nodes) {
  if (end - begin < kParallelBuildFaces || end - begin <= context.max_leaf) {
    build_range(context, begin, end, nodes);
    return;
  }
  const int index = static_cast<int>(nodes.size());
  nodes.push_back(BvhNode{-1, begin, end});
  const int middle = split_range(context, begin, end);
  std::vector<BvhNode> left, right;
  tbb::parallel_invoke([&] { build_range_parallel(context, begin, middle, left); },
                       [&] { build_range_parallel(context, middle, end, right); });
  const auto append = [&nodes](const std::vector<BvhNode>& subtree) {
    const int offset = static_cast<int>(nodes.size());
    for (BvhNode node : subtree) {
      if (!node.is_leaf()) node.right += offset;
      nodes.push_back(node);
    }
  };
  append(left);
  nodes[static_cast<std::size_t>(index)].right = static_cast<int>(nodes.size());
  append(right);
}

// Groups `owner`-indexed primitives by the tree position of their owner: a counting sort into owned/offset.
void group_by_owner(const std::vector<int>& owner, const std::vector<int>& position, std::vector<int>& owned,
                    std::vector<int>& offset) {
  offset.assign(position.size() + 1, 0);
  for (int o : owner) {
    if (o >= 0) ++offset[position[o] + 1];
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  owned.assign(offset.back(), -1);
  std::vector<int> cursor(offset.begin(), offset.end() - 1);
  for (int p = 0; p < static_cast<int>(owner.size()); ++p) {
    if (owner[p] >= 0) owned[cursor[position[owner[p]]]++] = p;
  }
}

// The swept box of face f: the union of its vertices' boxes.
FlatBox face_box(const BodyTopology& topology, const SweptBoxes& boxes, int f) {
  FlatBox b = boxes.vertices[topology.faces(f, 0)];
  b.expand(boxes.vertices[topology.faces(f, 1)]);
  b.expand(boxes.vertices[topology.faces(f, 2)]);
  return b;
}

}  // namespace

Bvh::Bvh(const BvhSettings& settings) : settings_(settings) {
  settings_.max_leaf_faces = std::max(1, settings_.max_leaf_faces);
}

void Bvh::build(const BodyTopology& topology, const SweptBoxes& boxes, const Vertices& start, const Vertices& end) {
  check_vertex_boxes(topology, boxes);
  const int face_count = topology.face_count();
  const bool parallel = settings_.parallel && face_count >= kParallelBuildFaces;
  std::vector<BuildItem> items(static_cast<std::size_t>(face_count));
  // Every item is filled whatever the others hold, so that the first bad face is found after the parallel fill.
  const auto fill_items = [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      BuildItem& item = items[static_cast<std::size_t>(f)];
      const FlatBox b = face_box(topology, boxes, f);
      for (int k = 0; k < 3; ++k) item.centroid[k] = static_cast<float>(b.min[k] + b.max[k]);
      item.low = simd::F32x4{static_cast<float>(b.min[0]), static_cast<float>(b.min[1]),
                             static_cast<float>(b.min[2]), 0.0f};
      item.negated_high = -simd::F32x4{static_cast<float>(b.max[0]), static_cast<float>(b.max[1]),
                                       static_cast<float>(b.max[2]), 0.0f};
      item.face = f;
    }
  };
  if (parallel) {
    tbb::parallel_for(tbb::blocked_range<int>(0, face_count, kParallelBuildFaces),
                      [&](const tbb::blocked_range<int>& r) { fill_items(r.begin(), r.end()); });
  } else {
    fill_items(0, face_count);
  }
  for (int f = 0; f < face_count; ++f) {
    const float* c = items[static_cast<std::size_t>(f)].centroid;
    if (std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2])) continue;
    // Also beyond the float range: the double-precision centre decides.
    const FlatBox b = face_box(topology, boxes, f);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(b.min[k] + b.max[k]))
        throw std::invalid_argument("bvh: face " + std::to_string(f) + " has a NaN or infinite box");
    }
  }
  nodes_.clear();
  nodes_.reserve(2 * static_cast<std::size_t>(face_count) / settings_.max_leaf_faces + 1);
  BuildContext context{items, settings_.max_leaf_faces};
  if (settings_.parallel) {
    build_range_parallel(context, 0, face_count, nodes_);
  } else {
    build_range(context, 0, face_count, nodes_);
  }
  face_order_.resize(static_cast<std::size_t>(face_count));
  for (int p = 0; p < face_count; ++p) {
    face_order_[static_cast<std::size_t>(p)] = items[static_cast<std::size_t>(p)].face;
  }

  std::vector<int> position(face_count);
  for (int i = 0; i < face_count; ++i) position[face_order_[i]] = i;
  // The vertices, the edges and the faces in tree order: three independent fills.
  const auto vertices_in_order = [&] {
    group_by_owner(topology.vertex_owner, position, owned_vertices_, vertex_offset_);
  };
  const auto edges_in_order = [&] {
    group_by_owner(topology.edge_owner, position, owned_edges_, edge_offset_);
    ordered_edges_.resize(2 * owned_edges_.size());
    for (std::size_t i = 0; i < owned_edges_.size(); ++i) {
      ordered_edges_[2 * i] = topology.edges[2 * owned_edges_[i]];
      ordered_edges_[2 * i + 1] = topology.edges[2 * owned_edges_[i] + 1];
    }
    packed_edges_.assign(ordered_edges_, 2);
  };
  const auto faces_in_order = [&] {
    ordered_faces_.resize(3 * static_cast<std::size_t>(face_count));
    for (int p = 0; p < face_count; ++p) {
      for (int k = 0; k < 3; ++k) ordered_faces_[3 * p + k] = topology.faces(face_order_[p], k);
    }
    packed_faces_.assign(ordered_faces_, 3);
  };
  if (parallel) {
    tbb::parallel_invoke(vertices_in_order, edges_in_order, faces_in_order);
  } else {
    vertices_in_order();
    edges_in_order();
    faces_in_order();
  }

  boxes_.clear();
  spheres_.clear();
  obbs_.clear();
  if (settings_.volume == VolumeKind::Obb) fit_obb_axes(topology, start, end);
  refit(boxes, parallel);
  built_looseness_ = looseness_;
  ++build_count_;
}

void Bvh::fit_obb_axes(const BodyTopology& topology, const Vertices& start, const Vertices& end) {
  obbs_.resize(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const detail::NodeTriangles node{&topology, face_order_.data() + nodes_[i].face_begin,
                                     face_order_.data() + nodes_[i].face_end, &start, &end};
    obbs_[i].axes = detail::node_obb_axes(node);
  }
}

void Bvh::check_vertex_boxes(const BodyTopology& topology, const SweptBoxes& boxes) {
  if (static_cast<int>(boxes.vertices.size()) != topology.vertex_count) {
    throw std::invalid_argument("bvh: " + std::to_string(boxes.vertices.size()) + " vertex boxes for " +
                                std::to_string(topology.vertex_count) + " vertices");
  }
}

}  // namespace clothcd::broadphase
