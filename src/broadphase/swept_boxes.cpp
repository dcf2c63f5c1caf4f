// Swept primitive boxes for continuous collision detection: with linear motion over the step, a primitive stays inside
// the box of its positions at t0 and t1, so that box (inflated by the thickness) bounds everything it sweeps.
#include "clothcd/broadphase/swept_boxes.hpp"

#include <limits>

namespace clothcd::broadphase {

FlatBox empty_flat_box() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return FlatBox{{inf, inf, inf}, {-inf, -inf, -inf}};
}

void compute_swept_boxes(const BodyTopology& topology, const Vertices& start, const Vertices& end, double thickness,
                         SweptBoxes& boxes) {
  const int vertex_count = static_cast<int>(start.rows());
  boxes.vertices.resize(vertex_count);
  const double* p = start.data();
  const double* q = end.data();
  for (int v = 0; v < vertex_count; ++v) {
    FlatBox& b = boxes.vertices[v];
    for (int k = 0; k < 3; ++k) {
      const double a = p[3 * v + k], c = q[3 * v + k];
      b.min[k] = (a < c ? a : c) - thickness;
      b.max[k] = (a < c ? c : a) + thickness;
    }
  }
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
