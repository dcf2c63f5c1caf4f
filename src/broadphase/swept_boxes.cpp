// Swept primitive boxes for continuous collision detection: with linear motion over the step, a primitive stays inside
// the box of its positions at t0 and t1, so that box bounds everything it sweeps. Each box is grown by half of the
// thickness: two primitives within the thickness of each other are within it along each axis, so grown boxes meet.
#include "clothcd/broadphase/swept_boxes.hpp"

#include <cmath>
#include <limits>

namespace clothcd::broadphase {
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

FlatBox empty_flat_box() {
  return FlatBox{{kInfinity, kInfinity, kInfinity}, {-kInfinity, -kInfinity, -kInfinity}};
}

namespace {

// x - half and x + half round to nearest, off by at most half a unit in the last place; moving the result outwards by
// 2^-52 of its magnitude (at least one unit in the last place, exact) and the smallest subnormal covers that rounding.
double grown_min(double x, double half) {
  if (half == 0.0) return x;
  const double r = x - half;
  return r - (std::fabs(r) * 0x1p-52 + 0x1p-1074);
}

double grown_max(double x, double half) {
  if (half == 0.0) return x;
  const double r = x + half;
  return r + (std::fabs(r) * 0x1p-52 + 0x1p-1074);
}

// The swept box of vertex v into `box`.
void vertex_box(const Vertices& start, const Vertices& end, double thickness, int v, FlatBox& box) {
  const double* p = start.data() + 3 * static_cast<std::ptrdiff_t>(v);
  const double* q = end.data() + 3 * static_cast<std::ptrdiff_t>(v);
  const double half = 0.5 * thickness;
  for (int k = 0; k < 3; ++k) {
    const double a = p[k], c = q[k];
    box.min[k] = grown_min(a < c ? a : c, half);
    box.max[k] = grown_max(a < c ? c : a, half);
  }
}

// The box of vertex v over the first `window` of the step (a power of two in (0, 1]) into `box`, as vertex_box makes
// it for the positions at 0 and `window`. The position at `window`, start + window (end - start), is rounded (twice,
// the product by a power of two being exact): it is moved outwards by 2^-50 of the larger end's magnitude (more than
// those two roundings) and the smallest subnormal. Rounding is monotone, so a longer window's box holds a shorter's.
void window_vertex_box(const Vertices& start, const Vertices& end, double window, double thickness, int v,
                       FlatBox& box) {
  const double* p = start.data() + 3 * static_cast<std::ptrdiff_t>(v);
  const double* q = end.data() + 3 * static_cast<std::ptrdiff_t>(v);
  vertex_box(start, start, thickness, v, box);
  for (int k = 0; k < 3; ++k) {
    if (p[k] == q[k]) continue;
    const double at_window = p[k] + window * (q[k] - p[k]);
    const double slack = std::fmax(std::fabs(p[k]), std::fabs(q[k])) * 0x1p-50 + 0x1p-1074;
    box.min[k] = std::fmin(box.min[k], grown_min(at_window - slack, 0.5 * thickness));
    box.max[k] = std::fmax(box.max[k], grown_max(at_window + slack, 0.5 * thickness));
  }
}

}  // namespace

void compute_window_vertex_boxes(const Vertices& start, const Vertices& end, double window, double thickness,
                                 SweptBoxes& boxes) {
  const int vertex_count = static_cast<int>(start.rows());
  boxes.vertices.resize(vertex_count);
  boxes.edges.clear();
  boxes.faces.clear();
  for (int v = 0; v < vertex_count; ++v) window_vertex_box(start, end, window, thickness, v, boxes.vertices[v]);
}

void compute_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness, SweptBoxes& boxes) {
  const int vertex_count = static_cast<int>(start.rows());
  boxes.vertices.resize(vertex_count);
  boxes.edges.clear();
  boxes.faces.clear();
  for (int v = 0; v < vertex_count; ++v) vertex_box(start, end, thickness, v, boxes.vertices[v]);
}

void update_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness,
                               const std::vector<std::uint8_t>& moved, SweptBoxes& boxes) {
  for (int v = 0; v < static_cast<int>(moved.size()); ++v) {
    if (moved[static_cast<std::size_t>(v)] != 0) vertex_box(start, end, thickness, v, boxes.vertices[v]);
  }
}

void compute_swept_boxes(const BodyTopology& topology, const Vertices& start, const Vertices& end, double thickness,
                         SweptBoxes& boxes) {
  compute_swept_vertex_boxes(start, end, thickness, boxes);
  const int edge_count = topology.edge_count();
  boxes.edges.resize(edge_count);
  for (int e = 0; e < edge_count; ++e) {
    FlatBox b = boxes.vertices[topology.edges[2 * e]];
    b.expand(boxes.vertices[topology.edges[2 * e + 1]]);
    boxes.edges[e] = b;
  }
  const int face_count = topology.face_count();
  boxes.faces.resize(face_count);
  for (int f = 0; f < face_count; ++f) {
    FlatBox b = boxes.vertices[topology.faces(f, 0)];
    b.expand(boxes.vertices[topology.faces(f, 1)]);
    b.expand(boxes.vertices[topology.faces(f, 2)]);
    boxes.faces[f] = b;
  }
}

}  // namespace clothcd::broadphase
