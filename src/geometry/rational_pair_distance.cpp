// The exact tier of the pair distances. The closest point of a convex set to a point is unique, and it is a vertex v
// exactly when p - v lies in the normal cone of v (non-positive dot products with the edges leaving v); for a
// triangle of non-zero area it is otherwise on an edge exactly when p is outside that edge's side and projects onto the
// closed edge (Ericson, "Real-Time Collision Detection", 5.1.5), else inside. Two segments: the squared distance
// F(s, u) = |a0 + s da - b0 - u db|^2 is convex on [0, 1]^2, so a parameter pair is a closest pair exactly when it
// satisfies the Karush-Kuhn-Tucker conditions there; the cells (corner, side, inside) are tested in the documented
// order, which is how ties between several closest pairs are broken.
#include "geometry/rational_pair_distance.hpp"

#include "geometry/rational_vector.hpp"

namespace clothcd::geometry {

namespace {

using rational::cross;
using rational::dot;
using rational::Vector;
using rational::operator+;
using rational::operator-;
using rational::operator*;

RationalDistance finish(DistanceType type, const mpq_class& w1, const mpq_class& w2, const Vector& gap) {
  RationalDistance result;
  result.squared_distance = dot(gap, gap);
  result.record.distance = rational::square_root(result.squared_distance);
  result.record.parameters = {w1.get_d(), w2.get_d()};
  result.record.direction = rational::unit_direction(gap);
  result.record.type = type;
  return result;
}

}  // namespace

RationalDistance rational_point_triangle_distance(const Eigen::Vector3d& p_in, const Eigen::Vector3d& t0,
                                                  const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Vector p = rational::from_double(p_in);
  const std::array<Vector, 3> t{rational::from_double(t0), rational::from_double(t1), rational::from_double(t2)};
  // edge[k] runs from t[k] to t[k + 1]; to_p[k] = p - t[k].
  const std::array<Vector, 3> edge{t[1] - t[0], t[2] - t[1], t[0] - t[2]};
  const std::array<Vector, 3> to_p{p - t[0], p - t[1], p - t[2]};
  // along[k]: p - t[k] along edge k; back[k]: p - t[k + 1] along edge k reversed.
  std::array<mpq_class, 3> along, back;
  for (int k = 0; k < 3; ++k) {
    along[k] = dot(edge[k], to_p[k]);
    back[k] = -dot(edge[k], to_p[(k + 1) % 3]);
  }
  // Vertex k: the edges leaving it are edge k and edge k - 1 reversed.
  for (int k = 0; k < 3; ++k) {
    if (sgn(along[k]) <= 0 && sgn(back[(k + 2) % 3]) <= 0) {
      const mpq_class w1 = k == 1 ? 1 : 0, w2 = k == 2 ? 1 : 0;
      return finish(static_cast<DistanceType>(static_cast<int>(DistanceType::PointVertex0) + k), w1, w2, to_p[k]);
    }
  }
  // Not at a vertex: on the edge of smallest index that holds the closest point, else inside.
  const Vector normal = cross(edge[0], t[2] - t[0]);
  const auto on_edge = [&](int k) {
    const mpq_class s = along[k] / dot(edge[k], edge[k]);
    const mpq_class w1 = k == 0 ? s : k == 1 ? mpq_class(1 - s) : mpq_class(0);
    const mpq_class w2 = k == 0 ? mpq_class(0) : k == 1 ? s : mpq_class(1 - s);
    return finish(static_cast<DistanceType>(static_cast<int>(DistanceType::PointEdge0) + k), w1, w2,
                  to_p[k] - s * edge[k]);
  };
  if (rational::is_zero(normal)) {
    // Zero area: the triangle is a segment, the union of its edges; the closest point is inside an edge of non-zero
    // length (it is no vertex), and inside every edge that attains the distance.
    int best = -1;
    mpq_class best_squared;
    for (int k = 0; k < 3; ++k) {
      const mpq_class length_squared = dot(edge[k], edge[k]);
      if (sgn(length_squared) == 0 || sgn(along[k]) <= 0 || sgn(back[k]) <= 0) continue;
      const Vector c = cross(edge[k], to_p[k]);
      const mpq_class squared = dot(c, c) / length_squared;
      if (best < 0 || squared < best_squared) best = k, best_squared = squared;
    }
    return on_edge(best);
  }
  for (int k = 0; k < 3; ++k) {
    // p is on the outer side of edge k (or in its plane through the normal) and projects onto it.
    if (sgn(dot(normal, cross(edge[k], to_p[k]))) <= 0 && sgn(along[k]) >= 0 && sgn(back[k]) >= 0) return on_edge(k);
  }
  const mpq_class area_squared = dot(normal, normal);
  const mpq_class w1 = dot(normal, cross(to_p[0], t[2] - t[0])) / area_squared;
  const mpq_class w2 = dot(normal, cross(edge[0], to_p[0])) / area_squared;
  return finish(DistanceType::PointFace, w1, w2, (dot(to_p[0], normal) / area_squared) * normal);
}

RationalDistance rational_segment_segment_distance(const Eigen::Vector3d& a0_in, const Eigen::Vector3d& a1_in,
                                                   const Eigen::Vector3d& b0_in, const Eigen::Vector3d& b1_in) {
  const std::array<Vector, 2> a{rational::from_double(a0_in), rational::from_double(a1_in)};
  const std::array<Vector, 2> b{rational::from_double(b0_in), rational::from_double(b1_in)};
  const Vector da = a[1] - a[0], db = b[1] - b[0];
  const mpq_class aa = dot(da, da), bb = dot(db, db), ab = dot(da, db);
  // Corners: F's partial derivatives are 2 da . x and -2 db . x with x = a(s) - b(u); they point inwards.
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const Vector x = a[i] - b[j];
      const int along_a = sgn(dot(da, x)), along_b = sgn(dot(db, x));
      if ((i == 0 ? along_a >= 0 : along_a <= 0) && (j == 0 ? along_b <= 0 : along_b >= 0)) {
        const auto type = static_cast<DistanceType>(static_cast<int>(DistanceType::VertexA0VertexB0) + 2 * i + j);
        return finish(type, i, j, x);
      }
    }
  }
  // Sides s = i: u = db . (a_i - b0) / |db|^2 strictly inside, and the s-derivative there pointing inwards.
  if (sgn(bb) > 0) {
    for (int i = 0; i < 2; ++i) {
      const Vector x = a[i] - b[0];
      const mpq_class f = dot(db, x);
      if (sgn(f) <= 0 || f >= bb) continue;
      const int slope = sgn(bb * dot(da, x) - f * ab);
      if (i == 0 ? slope >= 0 : slope <= 0) {
        const mpq_class u = f / bb;
        return finish(i == 0 ? DistanceType::VertexA0Edge : DistanceType::VertexA1Edge, i, u, x - u * db);
      }
    }
  }
  // Sides u = j, the same with the roles exchanged.
  if (sgn(aa) > 0) {
    for (int j = 0; j < 2; ++j) {
      const Vector y = b[j] - a[0];
      const mpq_class g = dot(da, y);
      if (sgn(g) <= 0 || g >= aa) continue;
      const int slope = sgn(aa * dot(db, y) - g * ab);
      if (j == 0 ? slope >= 0 : slope <= 0) {
        const mpq_class s = g / aa;
        return finish(j == 0 ? DistanceType::EdgeVertexB0 : DistanceType::EdgeVertexB1, s, j, s * da - y);
      }
    }
  }
  // No closest pair on the boundary of the parameter square: the segments are not parallel, and the common
  // perpendicular of their lines meets both inside.
  const Vector n = cross(da, db), w = b[0] - a[0];
  const mpq_class nn = dot(n, n);
  const mpq_class s = dot(cross(w, db), n) / nn, u = dot(cross(w, da), n) / nn;
  return finish(DistanceType::EdgeEdge, s, u, (a[0] + s * da) - (b[0] + u * db));
}

}  // namespace clothcd::geometry
