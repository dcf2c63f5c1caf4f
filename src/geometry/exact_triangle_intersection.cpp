// The rational reference of the triangle intersection test: exact edge clipping (see the header).
#include "geometry/exact_triangle_intersection.hpp"

#include <gmpxx.h>

#include <optional>
#include <vector>

namespace clothcd::geometry {

namespace {

using Q = mpq_class;
using V = std::array<Q, 3>;

V rational(const Eigen::Vector3d& p) {
  return {Q(p[0]), Q(p[1]), Q(p[2])};
}
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V along(const V& p, const V& d, const Q& t) {
  return {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]};
}
Q dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
bool is_zero(const V& a) {
  return sgn(a[0]) == 0 && sgn(a[1]) == 0 && sgn(a[2]) == 0;
}
bool equal(const V& a, const V& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

// Parameters t in [lo, hi] of the points p + t (q - p) of an edge in the other face.
struct Interval {
  Q lo, hi;
};

// x on the closed segment [m, n] (a point when m = n).
bool on_segment(const V& m, const V& n, const V& x) {
  const V f = sub(n, m), w = sub(x, m);
  if (is_zero(f)) return is_zero(w);
  if (!is_zero(cross(w, f))) return false;
  const Q along_f = dot(w, f);
  return sgn(along_f) >= 0 && along_f <= dot(f, f);
}

// The face an edge is clipped against: its normal, or, when degenerate, the corners ending the segment it covers.
struct OtherFace {
  std::array<V, 3> corners;
  V normal;
  bool degenerate = false;
  int first = 0, last = 0;  // degenerate: the corners farthest apart (equal when it is a point)

  explicit OtherFace(const std::array<V, 3>& y) : corners(y), normal(cross(sub(y[1], y[0]), sub(y[2], y[0]))) {
    degenerate = is_zero(normal);
    Q widest = 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = i + 1; j < 3; ++j) {
        const V d = sub(y[j], y[i]);
        const Q length = dot(d, d);
        if (length > widest) widest = length, first = i, last = j;
      }
    }
  }

  // Edge function of edge j: non-negative on the triangle's side (a non-degenerate face).
  Q edge_function(int j, const V& x) const {
    const V& from = corners[j];
    return dot(cross(sub(corners[(j + 1) % 3], from), sub(x, from)), normal);
  }

  std::optional<Interval> clip(const V& p, const V& q) const {
    return degenerate ? clip_segment(p, q) : clip_triangle(p, q);
  }

  std::optional<Interval> clip_triangle(const V& p, const V& q) const {
    const Q dp = dot(normal, sub(p, corners[0])), dq = dot(normal, sub(q, corners[0]));
    if (sgn(dp) == 0 && sgn(dq) == 0) {  // in the plane: the three edge half-planes
      Q lo = 0, hi = 1;
      for (int j = 0; j < 3; ++j) {
        const Q hp = edge_function(j, p), slope = edge_function(j, q) - hp;
        if (sgn(slope) == 0) {
          if (sgn(hp) < 0) return std::nullopt;
          continue;
        }
        const Q t = -hp / slope;
        if (sgn(slope) > 0) {
          if (t > lo) lo = t;
        } else if (t < hi) {
          hi = t;
        }
      }
      if (lo > hi) return std::nullopt;
      return Interval{lo, hi};
    }
    if (sgn(dp) * sgn(dq) > 0) return std::nullopt;
    const Q t = dp / (dp - dq);
    const V x = along(p, sub(q, p), t);
    for (int j = 0; j < 3; ++j) {
      if (sgn(edge_function(j, x)) < 0) return std::nullopt;
    }
    return Interval{t, t};
  }

  std::optional<Interval> clip_segment(const V& p, const V& q) const {
    const V &m = corners[first], &n = corners[last];
    const V d = sub(q, p), f = sub(n, m), w = sub(m, p);
    if (is_zero(d)) {
      if (!on_segment(m, n, p)) return std::nullopt;
      return Interval{Q(0), Q(0)};
    }
    const Q dd = dot(d, d);
    const V c = cross(d, f);
    if (is_zero(c)) {  // parallel (or the face is a point): collinear overlap
      if (!is_zero(cross(w, d))) return std::nullopt;
      Q lo = dot(w, d) / dd, hi = dot(sub(n, p), d) / dd;
      if (lo > hi) std::swap(lo, hi);
      if (lo < 0) lo = 0;
      if (hi > 1) hi = 1;
      if (lo > hi) return std::nullopt;
      return Interval{lo, hi};
    }
    if (sgn(dot(w, c)) != 0) return std::nullopt;  // skew lines
    const Q cc = dot(c, c);
    const Q t = dot(cross(w, f), c) / cc, u = dot(cross(w, d), c) / cc;
    if (sgn(t) < 0 || t > 1 || sgn(u) < 0 || u > 1) return std::nullopt;
    return Interval{t, t};
  }

  // (w1, w2) of a point x of the face.
  std::array<double, 2> weights(const V& x) const {
    Q w[3] = {0, 0, 0};
    if (!degenerate) {
      const Q nn = dot(normal, normal);
      w[1] = dot(normal, cross(sub(x, corners[0]), sub(corners[2], corners[0]))) / nn;
      w[2] = dot(normal, cross(sub(corners[1], corners[0]), sub(x, corners[0]))) / nn;
    } else if (first != last) {
      const V f = sub(corners[last], corners[first]);
      const Q u = dot(sub(x, corners[first]), f) / dot(f, f);
      w[first] += 1 - u;
      w[last] += u;
    }
    return {w[1].get_d(), w[2].get_d()};
  }
};

// All six corners in one plane: every triple product of their differences from the first vanishes.
bool coplanar(const std::array<V, 3>& a, const std::array<V, 3>& b) {
  std::array<V, 5> d;
  for (int i = 0; i < 5; ++i) d[i] = sub(i < 2 ? a[i + 1] : b[i - 2], a[0]);
  for (int i = 0; i < 5; ++i) {
    for (int j = i + 1; j < 5; ++j) {
      for (int k = j + 1; k < 5; ++k) {
        if (sgn(dot(d[i], cross(d[j], d[k]))) != 0) return false;
      }
    }
  }
  return true;
}

// x in the hull of the shared corners (at most two distinct points here).
bool in_hull(const std::vector<V>& hull, const V& x) {
  if (hull.empty()) return false;
  if (hull.size() == 1) return equal(hull[0], x);
  return on_segment(hull[0], hull[1], x);
}

}  // namespace

TriangleContact exact_intersect_triangles(const Triangle& a, const Triangle& b, const SharedCorners& shared) {
  const std::array<V, 3> ra = {rational(a[0]), rational(a[1]), rational(a[2])};
  const std::array<V, 3> rb = {rational(b[0]), rational(b[1]), rational(b[2])};
  TriangleContact contact;
  contact.coplanar = coplanar(ra, rb);
  // Three shared corners: both triangles are the hull of the shared corners, so nothing lies beyond it.
  if (shared.count == 3) return contact;
  std::vector<V> hull;
  for (int k = 0; k < shared.count; ++k) {
    const V& corner = ra[shared.pairs[k][0]];
    if (hull.empty() || !equal(hull[0], corner)) hull.push_back(corner);
  }
  for (int face = 0; face < 2; ++face) {
    const std::array<V, 3>& edges = face == 0 ? ra : rb;
    const OtherFace other(face == 0 ? rb : ra);
    for (int k = 0; k < 3; ++k) {
      const V &p = edges[k], d = sub(edges[(k + 1) % 3], p);
      const std::optional<Interval> interval = other.clip(p, edges[(k + 1) % 3]);
      if (!interval) continue;
      for (const Q* t : {&interval->lo, &interval->hi}) {
        const V x = along(p, d, *t);
        if (in_hull(hull, x)) continue;
        contact.intersect = true;
        contact.edge_face = face;
        contact.edge = k;
        contact.edge_parameter = t->get_d();
        contact.face_weights = other.weights(x);
        return contact;
      }
    }
  }
  return contact;
}

}  // namespace clothcd::geometry
