// Axis-aligned boxes and minimal bounding spheres. The sphere is E. Welzl, "Smallest enclosing disks (balls and
// ellipsoids)", 1991, in its iterative move-to-front form over a shuffled point order (expected linear time in 3-D).
#include "clothcd/geometry/simple_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "power_of_two_scale.hpp"

namespace clothcd::geometry {
namespace {

using Point = Eigen::Vector3d;

// A ball counts a point as inside up to a relative slack, so round-off cannot make the nested loops restart forever.
bool covers(const Sphere& s, const Point& p) {
  const double r = s.radius * (1.0 + 1e-12) + 1e-300;
  return s.radius >= 0 && (p - s.center).squaredNorm() <= r * r;
}

Sphere ball_of(const Point& a) { return {a, 0.0}; }

Sphere ball_of(const Point& a, const Point& b) { return {0.5 * (a + b), 0.5 * (a - b).norm()}; }

// The smallest ball with a, b, c on its boundary: the circumscribed circle's ball; for (near-)collinear points the ball
// over the farthest pair.
Sphere ball_of(const Point& a, const Point& b, const Point& c) {
  const Point ab = b - a, ac = c - a;
  const Point n = ab.cross(ac);
  const double n2 = n.squaredNorm();
  if (n2 <= 1e-24 * ab.squaredNorm() * ac.squaredNorm()) {
    Sphere best = ball_of(a, b);
    for (const Sphere& s : {ball_of(a, c), ball_of(b, c)}) best = s.radius > best.radius ? s : best;
    return best;
  }
  const Point offset = (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n2);
  return {a + offset, offset.norm()};
}

// The ball through four points; for (near-)coplanar points the smallest of the 3-point balls that holds all four.
Sphere ball_of(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Point ab = b - a, ac = c - a, ad = d - a;
  const double det = ab.dot(ac.cross(ad));
  const double size = ab.norm() * ac.norm() * ad.norm();
  if (std::abs(det) > 1e-12 * size) {
    const Point offset =
        (ab.squaredNorm() * ac.cross(ad) + ac.squaredNorm() * ad.cross(ab) + ad.squaredNorm() * ab.cross(ac)) /
        (2.0 * det);
    return {a + offset, offset.norm()};
  }
  Sphere best;
  const Point pts[4] = {a, b, c, d};
  for (int skip = 0; skip < 4; ++skip) {
    Point tri[3];
    for (int i = 0, k = 0; i < 4; ++i)
      if (i != skip) tri[k++] = pts[i];
    const Sphere s = ball_of(tri[0], tri[1], tri[2]);
    if (covers(s, pts[skip]) && (best.radius < 0 || s.radius < best.radius)) best = s;
  }
  return best.radius >= 0 ? best : ball_of(a, b, c);
}

}  // namespace

Aabb compute_aabb(const Vertices& points) {
  Aabb box;
  if (points.rows() == 0) return box;
  box.min = points.colwise().minCoeff().transpose();
  box.max = points.colwise().maxCoeff().transpose();
  return box;
}

Aabb compute_aabb(const Vertices& points, const std::vector<int>& indices) {
  Aabb box;
  for (int i : indices) box.expand(points.row(i).transpose());
  return box;
}

Sphere compute_bounding_sphere(const Vertices& points) {
  const auto n = static_cast<size_t>(points.rows());
  if (n == 0) return {};
  if (const int exponent = detail::far_scale_exponent(points)) {  // squared distances would overflow or underflow
    Sphere s = compute_bounding_sphere(points * std::ldexp(1.0, -exponent));
    s.center *= std::ldexp(1.0, exponent);
    s.radius *= std::ldexp(1.0, exponent);
    return s;
  }
  std::vector<Point> p(n);
  for (size_t i = 0; i < n; ++i) p[i] = points.row(Eigen::Index(i)).transpose();
  std::shuffle(p.begin(), p.end(), std::mt19937_64(0x5eed));
  Sphere s = ball_of(p[0]);
  for (size_t i = 1; i < n; ++i) {
    if (covers(s, p[i])) continue;
    s = ball_of(p[i]);
    for (size_t j = 0; j < i; ++j) {
      if (covers(s, p[j])) continue;
      s = ball_of(p[i], p[j]);
      for (size_t k = 0; k < j; ++k) {
        if (covers(s, p[k])) continue;
        s = ball_of(p[i], p[j], p[k]);
        for (size_t l = 0; l < k; ++l) {
          if (!covers(s, p[l])) s = ball_of(p[i], p[j], p[k], p[l]);
        }
      }
    }
  }
  // Guarantee containment whatever round-off did to the support sets.
  double r2 = 0.0;
  for (const Point& q : p) r2 = std::max(r2, (q - s.center).squaredNorm());
  double radius = std::sqrt(r2);
  while (radius * radius < r2) radius = std::nextafter(radius, std::numeric_limits<double>::infinity());
  s.radius = std::max(s.radius, radius);
  return s;
}

Sphere compute_bounding_sphere_naive(const Vertices& points) {
  if (points.rows() == 0) return {};
  if (const int exponent = detail::far_scale_exponent(points)) {
    Sphere s = compute_bounding_sphere_naive(points * std::ldexp(1.0, -exponent));
    s.center *= std::ldexp(1.0, exponent);
    s.radius *= std::ldexp(1.0, exponent);
    return s;
  }
  const Aabb box = compute_aabb(points);
  Sphere s{0.5 * (box.min + box.max), 0.0};
  s.radius = std::sqrt((points.rowwise() - s.center.transpose()).rowwise().squaredNorm().maxCoeff());
  return s;
}

}  // namespace clothcd::geometry
