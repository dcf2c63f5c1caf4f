// Closest points for the thickness test of the CCD (Ericson, "Real-Time Collision Detection", 5.1.2, 5.1.5, 5.1.9).
//
// The minimum of a point-triangle or segment-segment distance is attained either in the interior of both primitives
// (the projection onto the plane, or the common perpendicular of the two lines) or on the boundary, where it is a
// point-segment distance. Taking the minimum over all these candidates needs no case analysis that degenerates, and
// point-segment distances (clamped projection) are well conditioned. The interior candidate is only formed when the
// primitive is far from degenerate (sine above 1e-8), so its error stays a small multiple of the unit roundoff / 1e-8
// times the pair's extent; the thickness test covers that with its margin. When the interior candidate lies on both
// primitives it is the minimum, and the boundary is skipped.
#include "geometry/pair_distance.hpp"

#include <algorithm>
#include <cmath>

namespace clothcd::geometry {

namespace {

constexpr double kMinSineSquared = 1e-16;

// Parameter in [0, 1] of the point of segment a b closest to p (0 for a zero-length segment).
double segment_parameter(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d e = b - a;
  const double length_squared = e.squaredNorm();
  if (!(length_squared > 0.0)) return 0.0;
  return std::clamp(e.dot(p - a) / length_squared, 0.0, 1.0);
}

// The closest candidate pair so far, compared by squared distance (one square root at the end instead of one per
// candidate; the square root is monotonic, so the same candidate wins).
struct Nearest {
  double distance_squared;
  ClosestPoints points;

  Nearest(const Eigen::Vector3d& first, const Eigen::Vector3d& second)
      : distance_squared((first - second).squaredNorm()), points{0.0, {0.0, 0.0}, first, second} {}

  void keep_closer(const Eigen::Vector3d& first, const Eigen::Vector3d& second, std::array<double, 2> parameters) {
    const double d2 = (first - second).squaredNorm();
    if (d2 < distance_squared) {
      distance_squared = d2;
      points.parameters = parameters;
      points.first = first;
      points.second = second;
    }
  }

  // The boundary minimum with its distance.
  ClosestPoints finish() {
    points.distance = std::sqrt(distance_squared);
    return points;
  }
};

// r in the plane spanned by u and v (normal n = u x v): the coordinates (x, y) of its projection, r = x u + y v + z n,
// from Cramer's rule with cross products, and its height |r . n| / |n| above the plane. False when u and v are nearly
// parallel (sine at most 1e-8) or zero.
struct PlaneCoordinates {
  double x = 0.0;
  double y = 0.0;
  double height = 0.0;
};

bool plane_coordinates(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& r,
                       PlaneCoordinates& out) {
  const Eigen::Vector3d n = u.cross(v);
  const double n2 = n.squaredNorm();
  if (!(n2 > kMinSineSquared * u.squaredNorm() * v.squaredNorm())) return false;
  out.x = r.cross(v).dot(n) / n2;
  out.y = u.cross(r).dot(n) / n2;
  out.height = std::abs(r.dot(n)) / std::sqrt(n2);
  return true;
}

}  // namespace

ClosestPoints point_triangle_closest(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                     const Eigen::Vector3d& t2) {
  // The interior candidate first: when p projects inside the triangle, the plane distance is the minimum (every
  // boundary point is at least that far), and the boundary candidates are not needed.
  const Eigen::Vector3d e1 = t1 - t0;
  const Eigen::Vector3d e2 = t2 - t0;
  PlaneCoordinates w;  // barycentric weights of the projection
  if (plane_coordinates(e1, e2, p - t0, w) && w.x >= 0.0 && w.y >= 0.0 && w.x + w.y <= 1.0) {
    return {w.height, {w.x, w.y}, p, t0 + w.x * e1 + w.y * e2};
  }
  Nearest nearest(p, t0);
  const double s01 = segment_parameter(p, t0, t1);
  nearest.keep_closer(p, t0 + s01 * (t1 - t0), {s01, 0.0});
  const double s02 = segment_parameter(p, t0, t2);
  nearest.keep_closer(p, t0 + s02 * (t2 - t0), {0.0, s02});
  const double s12 = segment_parameter(p, t1, t2);
  nearest.keep_closer(p, t1 + s12 * (t2 - t1), {1.0 - s12, s12});
  return nearest.finish();
}

ClosestPoints segment_segment_closest(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                                      const Eigen::Vector3d& b1) {
  const Eigen::Vector3d da = a1 - a0;
  const Eigen::Vector3d db = b1 - b0;
  // The interior candidate first: when the common perpendicular of the two lines meets both segments, its length is
  // the minimum, and the endpoint candidates are not needed.
  // With b0 - a0 = s da - u db + z n, the perpendicular joins a0 + s da and b0 + u db.
  PlaneCoordinates c;
  if (plane_coordinates(da, db, b0 - a0, c)) {
    const double s = c.x, u = -c.y;
    if (s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0) return {c.height, {s, u}, a0 + s * da, b0 + u * db};
  }
  Nearest nearest(a0, b0);
  const double u0 = segment_parameter(a0, b0, b1);
  nearest.keep_closer(a0, b0 + u0 * db, {0.0, u0});
  const double u1 = segment_parameter(a1, b0, b1);
  nearest.keep_closer(a1, b0 + u1 * db, {1.0, u1});
  const double s0 = segment_parameter(b0, a0, a1);
  nearest.keep_closer(a0 + s0 * da, b0, {s0, 0.0});
  const double s1 = segment_parameter(b1, a0, a1);
  nearest.keep_closer(a0 + s1 * da, b1, {s1, 1.0});
  return nearest.finish();
}

}  // namespace clothcd::geometry
