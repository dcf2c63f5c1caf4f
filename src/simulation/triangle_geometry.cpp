// Triangle-triangle intersection and distance for the independent frame check. Intersection: two triangles meet iff an
// edge of one meets the other (segment-triangle by orientation signs, as in Segura and Feito 2001), with coplanar pairs
// reduced to 2D; distance: the minimum over the 6 vertex-triangle and 9 edge-edge distances (Ericson's closest points,
// geometry/pair_distance.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "clothcd/simulation/intersection_check.hpp"
#include "geometry/pair_distance.hpp"

namespace clothcd::simulation {
namespace {

using geometry::segment_segment_distance_squared;

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

double orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment_2d(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect_2d(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const double d1 = orient2d(a, b, p), d2 = orient2d(a, b, q), d3 = orient2d(p, q, a), d4 = orient2d(p, q, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment_2d(a, b, p)) || (d2 == 0 && on_segment_2d(a, b, q)) ||
         (d3 == 0 && on_segment_2d(p, q, a)) || (d4 == 0 && on_segment_2d(p, q, b));
}

bool point_in_triangle_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = orient2d(a, b, p), d2 = orient2d(b, c, p), d3 = orient2d(c, a, p);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

/// Drops the coordinate along which the triangle's normal is largest.
Vec2 project(const Vec3& p, int drop) {
  return drop == 0 ? Vec2(p.y(), p.z()) : drop == 1 ? Vec2(p.x(), p.z()) : Vec2(p.x(), p.y());
}

/// Segment pq against triangle abc lying in the same plane (non-degenerate triangle).
bool segment_triangle_coplanar(const Vec3& p, const Vec3& q, const Triangle& t, const Vec3& normal) {
  int drop = 0;
  normal.cwiseAbs().maxCoeff(&drop);
  const Vec2 p2 = project(p, drop), q2 = project(q, drop);
  const Vec2 a = project(t.a, drop), b = project(t.b, drop), c = project(t.c, drop);
  return point_in_triangle_2d(p2, a, b, c) || point_in_triangle_2d(q2, a, b, c) ||
         segments_intersect_2d(p2, q2, a, b) || segments_intersect_2d(p2, q2, b, c) ||
         segments_intersect_2d(p2, q2, c, a);
}

/// Segment pq against a non-degenerate triangle.
bool segment_triangle(const Vec3& p, const Vec3& q, const Triangle& t, const Vec3& normal) {
  const double dp = orient3d(t.a, t.b, t.c, p), dq = orient3d(t.a, t.b, t.c, q);
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0)) return false;
  if (dp == 0 && dq == 0) return segment_triangle_coplanar(p, q, t, normal);
  const double s1 = orient3d(p, q, t.a, t.b), s2 = orient3d(p, q, t.b, t.c), s3 = orient3d(p, q, t.c, t.a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

Vec3 normal_of(const Triangle& t) { return (t.b - t.a).cross(t.c - t.a); }

bool is_degenerate(const Triangle& t, const Vec3& normal) {
  const double scale = std::max({(t.b - t.a).squaredNorm(), (t.c - t.a).squaredNorm(), (t.c - t.b).squaredNorm()});
  return normal.squaredNorm() <= 1e-24 * scale * scale;
}

// Squared distance from p to the non-degenerate triangle t, with the simulation's rounding.
double distance_squared(const Vec3& p, const Triangle& t) {
  return geometry::point_triangle_distance_squared(p, t.a, t.b, t.c, geometry::FaceRounding::Reciprocal);
}

double edges_distance_squared(const Triangle& t, const Triangle& u) {
  const Vec3* tv[3] = {&t.a, &t.b, &t.c};
  const Vec3* uv[3] = {&u.a, &u.b, &u.c};
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      best = std::min(best, segment_segment_distance_squared(*tv[i], *tv[(i + 1) % 3], *uv[j], *uv[(j + 1) % 3]));
    }
  }
  return best;
}

/// Edges of a degenerate triangle `d` against triangle `u` (which may be degenerate too).
bool degenerate_intersects(const Triangle& d, const Triangle& u, const Vec3& u_normal, bool u_degenerate) {
  if (u_degenerate) return edges_distance_squared(d, u) == 0.0;
  return segment_triangle(d.a, d.b, u, u_normal) || segment_triangle(d.b, d.c, u, u_normal) ||
         segment_triangle(d.c, d.a, u, u_normal);
}

}  // namespace

bool triangles_intersect(const Triangle& t, const Triangle& u) {
  const Vec3 nt = normal_of(t), nu = normal_of(u);
  const bool t_degenerate = is_degenerate(t, nt), u_degenerate = is_degenerate(u, nu);
  if (t_degenerate) return degenerate_intersects(t, u, nu, u_degenerate);
  if (u_degenerate) return degenerate_intersects(u, t, nt, false);
  return segment_triangle(t.a, t.b, u, nu) || segment_triangle(t.b, t.c, u, nu) || segment_triangle(t.c, t.a, u, nu) ||
         segment_triangle(u.a, u.b, t, nt) || segment_triangle(u.b, u.c, t, nt) || segment_triangle(u.c, u.a, t, nt);
}

double triangle_distance(const Triangle& t, const Triangle& u) {
  if (triangles_intersect(t, u)) return 0.0;
  double best = edges_distance_squared(t, u);
  if (!is_degenerate(u, normal_of(u))) {
    best = std::min({best, distance_squared(t.a, u), distance_squared(t.b, u), distance_squared(t.c, u)});
  }
  if (!is_degenerate(t, normal_of(t))) {
    best = std::min({best, distance_squared(u.a, t), distance_squared(u.b, t), distance_squared(u.c, t)});
  }
  return std::sqrt(best);
}

}  // namespace clothcd::simulation
