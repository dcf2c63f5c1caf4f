// The reference pair distances by enumeration. The squared distance of two convex primitives is a convex quadratic of
// their parameters; its minimum over the parameter domain is at the unconstrained critical point when that lies
// strictly inside, or else on the domain's boundary, whose pieces are point-segment distances: each one's minimum is
// at the clamped projection, an end point (a vertex-vertex candidate) or a point strictly inside the segment (a
// vertex-edge candidate). The candidates are listed in the documented tie order, so the first minimum is the type.
#include "geometry/exact_pair_distance.hpp"

#include <optional>
#include <vector>

#include "geometry/rational_vector.hpp"

namespace clothcd::geometry {

namespace {

using rational::cross;
using rational::dot;
using rational::Vector;
using rational::operator+;
using rational::operator-;
using rational::operator*;

struct Candidate {
  mpq_class squared_distance;
  DistanceType type;
};

// The squared distance of p and the segment a b when p projects strictly inside it.
std::optional<mpq_class> inside_segment(const Vector& p, const Vector& a, const Vector& b) {
  const Vector e = b - a;
  const mpq_class length_squared = dot(e, e);
  if (sgn(length_squared) == 0) return std::nullopt;
  const mpq_class t = dot(p - a, e) / length_squared;
  if (sgn(t) <= 0 || t >= 1) return std::nullopt;
  const Vector gap = (p - a) - t * e;
  return dot(gap, gap);
}

ExactPairDistance first_minimum(const std::vector<Candidate>& candidates) {
  const Candidate* best = &candidates.front();
  for (const Candidate& c : candidates)
    if (c.squared_distance < best->squared_distance) best = &c;
  return {best->squared_distance, best->type};
}

DistanceType offset(DistanceType first, int k) {
  return static_cast<DistanceType>(static_cast<int>(first) + k);
}

}  // namespace

ExactPairDistance exact_point_triangle_distance(const Eigen::Vector3d& p_in, const Eigen::Vector3d& t0,
                                                const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Vector p = rational::from_double(p_in);
  const std::array<Vector, 3> t{rational::from_double(t0), rational::from_double(t1), rational::from_double(t2)};
  std::vector<Candidate> candidates;
  for (int k = 0; k < 3; ++k) candidates.push_back({dot(p - t[k], p - t[k]), offset(DistanceType::PointVertex0, k)});
  for (int k = 0; k < 3; ++k) {
    if (const auto d2 = inside_segment(p, t[k], t[(k + 1) % 3]))
      candidates.push_back({*d2, offset(DistanceType::PointEdge0, k)});
  }
  // The projection onto the plane, when the triangle has an area: barycentric weights by Cramer's rule.
  const Vector e1 = t[1] - t[0], e2 = t[2] - t[0], r = p - t[0];
  const Vector n = cross(e1, e2);
  const mpq_class nn = dot(n, n);
  if (sgn(nn) != 0) {
    const mpq_class w1 = dot(cross(r, e2), n) / nn, w2 = dot(cross(e1, r), n) / nn;
    if (sgn(w1) > 0 && sgn(w2) > 0 && w1 + w2 < 1) {
      const mpq_class height = dot(r, n);
      candidates.push_back({height * height / nn, DistanceType::PointFace});
    }
  }
  return first_minimum(candidates);
}

ExactPairDistance exact_segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                                 const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  const std::array<Vector, 2> a{rational::from_double(a0), rational::from_double(a1)};
  const std::array<Vector, 2> b{rational::from_double(b0), rational::from_double(b1)};
  std::vector<Candidate> candidates;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      candidates.push_back({dot(a[i] - b[j], a[i] - b[j]), offset(DistanceType::VertexA0VertexB0, 2 * i + j)});
  for (int i = 0; i < 2; ++i)
    if (const auto d2 = inside_segment(a[i], b[0], b[1]))
      candidates.push_back({*d2, offset(DistanceType::VertexA0Edge, i)});
  for (int j = 0; j < 2; ++j)
    if (const auto d2 = inside_segment(b[j], a[0], a[1]))
      candidates.push_back({*d2, offset(DistanceType::EdgeVertexB0, j)});
  // The common perpendicular of the lines, when they are not parallel: a0 + s da and b0 + u db with
  // (a0 + s da - b0 - u db) . da = 0 and . db = 0 (Cramer's rule).
  const Vector da = a[1] - a[0], db = b[1] - b[0], r = a[0] - b[0];
  const mpq_class aa = dot(da, da), bb = dot(db, db), ab = dot(da, db), ar = dot(da, r), br = dot(db, r);
  const mpq_class det = aa * bb - ab * ab;
  if (sgn(det) != 0) {
    const mpq_class s = (ab * br - bb * ar) / det, u = (aa * br - ab * ar) / det;
    if (sgn(s) > 0 && s < 1 && sgn(u) > 0 && u < 1) {
      const Vector gap = (r + s * da) - u * db;
      candidates.push_back({dot(gap, gap), DistanceType::EdgeEdge});
    }
  }
  return first_minimum(candidates);
}

}  // namespace clothcd::geometry
