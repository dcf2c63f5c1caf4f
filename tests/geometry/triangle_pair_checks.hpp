#pragma once
// Helpers of the triangle intersection tests: the comparison of the fast test with the rational reference, the check
// of a reported crossing point, and generators of triangle pairs (random, on integer grids, touching by construction).

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "geometry/exact_triangle_intersection.hpp"
#include "geometry/triangle_intersection.hpp"

namespace clothcd::test {

using geometry::SharedCorners;
using geometry::Triangle;
using geometry::TriangleContact;

/// The pair as text, to the last bit (for failure messages).
inline std::string describe(const Triangle& a, const Triangle& b, const SharedCorners& shared) {
  std::ostringstream out;
  out.precision(17);
  for (const Triangle* t : {&a, &b}) {
    out << "{";
    for (const Eigen::Vector3d& p : *t) out << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    out << "} ";
  }
  out << "shared:";
  for (int k = 0; k < shared.count; ++k) out << " " << shared.pairs[k][0] << "-" << shared.pairs[k][1];
  return out.str();
}

/// The point of the reported crossing on its edge, and on the other face.
inline std::array<Eigen::Vector3d, 2> crossing_points(const Triangle& a, const Triangle& b,
                                                      const TriangleContact& contact) {
  const Triangle& edge_face = contact.edge_face == 0 ? a : b;
  const Triangle& other = contact.edge_face == 0 ? b : a;
  const double s = contact.edge_parameter, w1 = contact.face_weights[0], w2 = contact.face_weights[1];
  const Eigen::Vector3d on_edge = (1.0 - s) * edge_face[contact.edge] + s * edge_face[(contact.edge + 1) % 3];
  const Eigen::Vector3d on_face = (1.0 - w1 - w2) * other[0] + w1 * other[1] + w2 * other[2];
  return {on_edge, on_face};
}

/// The largest coordinate magnitude of the pair (the scale rounding errors are relative to).
inline double magnitude(const Triangle& a, const Triangle& b) {
  double m = 0.0;
  for (const Triangle* t : {&a, &b}) {
    for (const Eigen::Vector3d& p : *t) m = std::max(m, p.cwiseAbs().maxCoeff());
  }
  return m;
}

/// "" when the crossing is a valid one: parameters in range, the point on the edge and the point by its weights on
/// the other face within `tolerance` (relative to the pair's magnitude), and not a shared corner (the edge's end at a
/// shared corner, or the shared edge itself; its rounded position may still be a shared corner's, next to a sliver);
/// else what is wrong.
inline std::string crossing_error(const Triangle& a, const Triangle& b, const SharedCorners& shared,
                                  const TriangleContact& contact, double tolerance) {
  const double s = contact.edge_parameter, w1 = contact.face_weights[0], w2 = contact.face_weights[1];
  if (contact.edge_face < 0 || contact.edge_face > 1 || contact.edge < 0 || contact.edge > 2) return "bad edge";
  if (!(s >= 0.0 && s <= 1.0)) return "edge parameter out of [0, 1]";
  if (!(w1 >= 0.0 && w2 >= 0.0 && w1 + w2 <= 1.0 + 1e-15)) return "face weights off the triangle";
  const auto [on_edge, on_face] = crossing_points(a, b, contact);
  const double gap = (on_edge - on_face).norm(), allowed = tolerance * magnitude(a, b);
  if (!(gap <= allowed)) return "edge point and face point " + std::to_string(gap) + " apart";
  // The crossing is not at a shared corner, nor on the edge the faces share.
  int shared_in_edge = 0;
  for (int k = 0; k < shared.count; ++k) {
    const int corner = contact.edge_face == 0 ? shared.pairs[k][0] : shared.pairs[k][1];
    if (corner == contact.edge && s == 0.0) return "crossing at a shared corner";
    if (corner == (contact.edge + 1) % 3 && s == 1.0) return "crossing at a shared corner";
    if (corner == contact.edge || corner == (contact.edge + 1) % 3) ++shared_in_edge;
  }
  if (shared_in_edge == 2) return "crossing on the shared edge";
  return "";
}

/// "" when the fast test and the reference agree on the pair (intersect, coplanar; the yes/no variant too) and the
/// fast test's crossing is valid; else a description of the disagreement.
inline std::string disagreement(const Triangle& a, const Triangle& b, const SharedCorners& shared = {},
                                double tolerance = 1e-9) {
  const TriangleContact fast = geometry::intersect_triangles(a, b, shared);
  const TriangleContact exact = geometry::exact_intersect_triangles(a, b, shared);
  std::string problem;
  if (fast.intersect != exact.intersect) {
    problem = std::string("intersect ") + (fast.intersect ? "true" : "false") + ", reference says otherwise";
  } else if (fast.coplanar != exact.coplanar) {
    problem = std::string("coplanar ") + (fast.coplanar ? "true" : "false") + ", reference says otherwise";
  } else if (geometry::triangles_intersect(a, b, shared) != exact.intersect) {
    problem = "triangles_intersect disagrees";
  } else if (fast.intersect) {
    problem = crossing_error(a, b, shared, fast, tolerance);
    if (problem.empty()) problem = crossing_error(a, b, shared, exact, tolerance);
  }
  return problem.empty() ? problem : problem + ": " + describe(a, b, shared);
}

/// A point with coordinates uniform in center +- half.
inline Eigen::Vector3d random_point(std::mt19937_64& random, const Eigen::Vector3d& center, double half) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return center + half * Eigen::Vector3d(unit(random), unit(random), unit(random));
}

/// A point of the integer grid [-range, range]^3.
inline Eigen::Vector3d grid_point(std::mt19937_64& random, int range) {
  std::uniform_int_distribution<int> coordinate(-range, range);
  return Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
}

/// The point one ulp from p along `axis`, up or down.
inline Eigen::Vector3d ulp_step(Eigen::Vector3d p, int axis, bool up) {
  p[axis] = std::nextafter(p[axis], up ? INFINITY : -INFINITY);
  return p;
}

/// The shared corners of b made of a's: b's corner j is a's corner `of_a[j]` (or its own when -1), listed in pairs.
inline SharedCorners share(const std::array<int, 3>& of_a) {
  SharedCorners shared;
  for (int j = 0; j < 3; ++j) {
    if (of_a[j] >= 0) shared.pairs[shared.count++] = {of_a[j], j};
  }
  return shared;
}

}  // namespace clothcd::test
