// Triangle-triangle intersection and distance for the independent frame check. Intersection: two triangles meet iff an
// edge of one meets the other (segment-triangle by orientation signs, as in Segura and Feito 2001), with coplanar pairs
// reduced to 2D; distance: the minimum over the 6 vertex-triangle and 9 edge-edge distances (Ericson, "Real-Time
// Collision Detection", 5.1.5 closest point on a triangle and 5.1.9 closest points of two segments).
#include <algorithm>
#include <cmath>
#include <limits>

#include "clothcd/simulation/intersection_check.hpp"
#include "simulation/primitive_distance.hpp"

namespace clothcd::simulation {
namespace {

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

/// Squared distance between segments p1q1 and p2q2 (Ericson 5.1.9, with its degenerate-segment branches).
double segment_segment_distance_squared(const Eigen::Vector3d& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-300;
  double s = 0, t = 0;
  if (a <= kTiny && e <= kTiny) return r.squaredNorm();
  if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).squaredNorm();
}

/// Squared distance from p to a non-degenerate triangle (Ericson 5.1.5, Voronoi regions).
double point_triangle_distance_squared(const Eigen::Vector3d& p, const Triangle& t) {
  const Vec3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Vec3 bp = p - t.b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (t.a + d1 / (d1 - d3) * ab)).squaredNorm();
  const Vec3 cp = p - t.c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (t.a + d2 / (d2 - d6) * ac)).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (t.b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (t.c - t.b))).squaredNorm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (t.a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

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
    best = std::min({best, point_triangle_distance_squared(t.a, u), point_triangle_distance_squared(t.b, u),
                     point_triangle_distance_squared(t.c, u)});
  }
  if (!is_degenerate(t, normal_of(t))) {
    best = std::min({best, point_triangle_distance_squared(u.a, t), point_triangle_distance_squared(u.b, t),
                     point_triangle_distance_squared(u.c, t)});
  }
  return std::sqrt(best);
}

}  // namespace clothcd::simulation
