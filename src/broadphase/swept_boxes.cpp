// Swept primitive boxes for continuous collision detection: with linear motion over the step, a primitive stays inside
// the box of its positions at t0 and t1, so that box bounds everything it sweeps. Each box is grown by half of the
// thickness: two primitives within the thickness of each other are within it along each axis, so grown boxes meet.
#include "broadphase/swept_boxes.hpp"

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

// Bounds [lo, hi] of x0 + t (x1 - x0) for t in [0, 1]. Rounded (three roundings), the value is off from the exact
// one by at most 5 units in the last place of the larger end's magnitude, so moving it outwards by 2^-50 of that
// magnitude (8 units, of which that subtraction's own rounding takes at most one) and the smallest subnormal covers
// it. t = 0 and t = 1 (and a coordinate that does not move) give the end exactly.
inline void interpolated_bounds(double x0, double x1, double t, double& lo, double& hi) {
  if (t == 0.0 || x0 == x1) {
    lo = hi = x0;
  } else if (t == 1.0) {
    lo = hi = x1;
  } else {
    const double at = x0 + t * (x1 - x0);
    const double slack = std::fmax(std::fabs(x0), std::fabs(x1)) * 0x1p-50 + 0x1p-1074;
    lo = at - slack;
    hi = at + slack;
  }
}

// The box of vertex v over the part [from, to] of the step (0 <= from < to <= 1) into `box`: the box of its positions
// at `from` and `to` (each rounded outwards, interpolated_bounds), grown by half the thickness. Linear motion over
// [from, to] stays between those two positions; [0, 1] is the whole step's swept box.
void part_vertex_box(const Vertices& start, const Vertices& end, double from, double to, double thickness, int v,
                     FlatBox& box) {
  const double* p = start.data() + 3 * static_cast<std::ptrdiff_t>(v);
  const double* q = end.data() + 3 * static_cast<std::ptrdiff_t>(v);
  const double half = 0.5 * thickness;
  for (int k = 0; k < 3; ++k) {
    double lo_from, hi_from, lo_to, hi_to;
    interpolated_bounds(p[k], q[k], from, lo_from, hi_from);
    interpolated_bounds(p[k], q[k], to, lo_to, hi_to);
    // Comparisons, not fmin / fmax: a NaN end reaches the box (where the hierarchy build refuses it).
    box.min[k] = grown_min(lo_from < lo_to ? lo_from : lo_to, half);
    box.max[k] = grown_max(hi_from < hi_to ? hi_to : hi_from, half);
  }
}

}  // namespace

void compute_part_vertex_boxes(const Vertices& start, const Vertices& end, double from, double to, double thickness,
                               SweptBoxes& boxes) {
  const int vertex_count = static_cast<int>(start.rows());
  boxes.vertices.resize(vertex_count);
  boxes.edges.clear();
  boxes.faces.clear();
  for (int v = 0; v < vertex_count; ++v) part_vertex_box(start, end, from, to, thickness, v, boxes.vertices[v]);
}

void compute_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness, SweptBoxes& boxes) {
  const int vertex_count = static_cast<int>(start.rows());
  boxes.vertices.resize(vertex_count);
  boxes.edges.clear();
  boxes.faces.clear();
  for (int v = 0; v < vertex_count; ++v) part_vertex_box(start, end, 0.0, 1.0, thickness, v, boxes.vertices[v]);
}

void update_swept_vertex_boxes(const Vertices& start, const Vertices& end, double thickness,
                               const std::vector<std::uint8_t>& moved, SweptBoxes& boxes) {
  for (int v = 0; v < static_cast<int>(moved.size()); ++v) {
    if (moved[static_cast<std::size_t>(v)] != 0) part_vertex_box(start, end, 0.0, 1.0, thickness, v, boxes.vertices[v]);
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
