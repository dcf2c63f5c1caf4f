// The vertex-face filter of the pair distances. After three cheap certain rejections (a box axis, a separating
// direction from approximate closest points, the triangle's plane)
// the closest point's cell is certified: vertex k when p - t_k has negative dot products with both edges leaving t_k
// (the inside of its normal cone), edge k when p lies strictly outside the edge's side and projects strictly inside
// it, the face when p lies strictly inside all three sides. Strict signs make the cell, and so the type, exact: no
// other feature holds the closest point (a strict side sign needs a non-zero area). The cell's squared distance is a
// quotient num / den of polynomials, compared with d^2 as the certain sign of d^2 den - num.
#include "geometry/pair_distance.hpp"

#include <algorithm>

#include "geometry/pair_distance_filter.hpp"
#include "geometry/pair_distance_separation.hpp"

namespace clothcd::geometry {

namespace {

using bounded::Bounded;
using bounded::BoundedVector;
using bounded::difference;
using bounded::sign;
using filter::Outcome;

// Some axis separates p from the triangle's box by more than d.
bool box_apart(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
               const Eigen::Vector3d& t2, double d) {
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = std::min({t0[axis], t1[axis], t2[axis]}), hi = std::max({t0[axis], t1[axis], t2[axis]});
    if (filter::gap_exceeds(p[axis], hi, d) || filter::gap_exceeds(lo, p[axis], d)) return true;
  }
  return false;
}

DistanceType offset(DistanceType first, int k) {
  return static_cast<DistanceType>(static_cast<int>(first) + k);
}

// Barycentric weights (w1, w2) of t_k + s (t_{k+1} - t_k), s in (0, 1] (a parameter strictly inside may round up to
// 1, hence the callers' clamp).
std::array<double, 2> edge_weights(int k, double s) {
  if (k == 0) return {s, 0.0};
  if (k == 1) return {1.0 - s, s};
  return {0.0, 1.0 - s};
}

Outcome point_triangle_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                              const Eigen::Vector3d& t2, double d, bool limited, PairDistance& out) {
  if (!filter::in_range({&p, &t0, &t1, &t2})) return Outcome::Undecided;
  if (limited && box_apart(p, t0, t1, t2, d)) return Outcome::Apart;
  const std::array<BoundedVector<1>, 3> to_p{difference(p, t0), difference(p, t1), difference(p, t2)};
  if (limited) {
    const Eigen::Vector3d guess = p - closest_point_on_triangle(p, t0, t1, t2);
    if (filter::separated_along(guess, d, to_p[0], to_p[1], to_p[2])) return Outcome::Apart;
  }
  // edge[k] runs from t_k to t_{k+1}; n = (t1 - t0) x (t2 - t0).
  const std::array<BoundedVector<1>, 3> edge{difference(t1, t0), difference(t2, t1), difference(t0, t2)};
  const BoundedVector<4> n = cross(edge[2], edge[0]);
  const Bounded<8> height = dot(to_p[0], n);
  const Bounded<11> area_squared = dot(n, n);
  // The plane's distance |height| / |n| is at most the triangle's.
  const int plane_within = limited ? filter::within_sign(height * height, area_squared, d) : 0;
  if (plane_within < 0) return Outcome::Apart;

  const std::array<BoundedVector<4>, 3> outward{cross(edge[0], to_p[0]), cross(edge[1], to_p[1]),
                                                cross(edge[2], to_p[2])};
  std::array<int, 3> side;  // +1: p strictly on the triangle's side of edge k
  for (int k = 0; k < 3; ++k) side[k] = sign(dot(n, outward[k]));
  if (side[0] > 0 && side[1] > 0 && side[2] > 0) {
    if (limited && plane_within == 0) return Outcome::Undecided;
    if (!bounded::accurate_length<filter::kNumeratorBits>(height) ||
        !bounded::accurate_length<filter::kDenominatorBits>(n, area_squared.value))
      return Outcome::Undecided;
    out.distance = filter::distance_from_squares(height.value * height.value, area_squared.value);
    const double inverse_area = 1.0 / area_squared.value;
    out.parameters = {dot(n, outward[2]).value * inverse_area, dot(n, outward[0]).value * inverse_area};
    out.direction = (height.value > 0.0 ? n.value : Eigen::Vector3d(-n.value)).normalized();
    out.type = DistanceType::PointFace;
    return Outcome::Found;
  }
  // along[k]: p - t_k along edge k; ahead[k]: p - t_{k+1} along edge k.
  std::array<int, 3> along, ahead;
  for (int k = 0; k < 3; ++k) {
    along[k] = sign(dot(edge[k], to_p[k]));
    ahead[k] = sign(dot(edge[k], to_p[(k + 1) % 3]));
  }
  for (int k = 0; k < 3; ++k) {
    if (along[k] < 0 && ahead[(k + 2) % 3] > 0) {
      const Bounded<5> squared = dot(to_p[k], to_p[k]);
      if (limited) {
        const int within = filter::within_sign(squared, d);
        if (within < 0) return Outcome::Apart;
        if (within == 0) return Outcome::Undecided;
      }
      if (!bounded::accurate_length<filter::kNumeratorBits>(to_p[k], squared.value)) return Outcome::Undecided;
      out.distance = filter::distance_from_squares(squared.value, 1.0);
      out.parameters = {k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
      out.direction = to_p[k].value.normalized();
      out.type = offset(DistanceType::PointVertex0, k);
      return Outcome::Found;
    }
    if (side[k] < 0 && along[k] > 0 && ahead[k] < 0) {
      const Bounded<11> squared_area = dot(outward[k], outward[k]);
      const Bounded<5> length_squared = dot(edge[k], edge[k]);
      if (limited) {
        const int within = filter::within_sign(squared_area, length_squared, d);
        if (within < 0) return Outcome::Apart;
        if (within == 0) return Outcome::Undecided;
      }
      if (!bounded::accurate_length<filter::kNumeratorBits>(outward[k], squared_area.value) ||
          !bounded::accurate_length<filter::kDenominatorBits>(edge[k], length_squared.value))
        return Outcome::Undecided;
      out.distance = filter::distance_from_squares(squared_area.value, length_squared.value);
      out.parameters = edge_weights(k, std::min(dot(edge[k], to_p[k]).value / length_squared.value, 1.0));
      out.direction = outward[k].value.cross(edge[k].value).normalized();
      out.type = offset(DistanceType::PointEdge0, k);
      return Outcome::Found;
    }
  }
  return Outcome::Undecided;
}

}  // namespace

bool point_triangle_within(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                           const Eigen::Vector3d& t2, double d, PairDistance& out) {
  return filter::decide_within(
      d, out,
      [&](double limit, bool limited, PairDistance& record) {
        return point_triangle_filter(p, t0, t1, t2, limit, limited, record);
      },
      [&] { return rational_point_triangle_distance(p, t0, t1, t2); });
}

PairDistance point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                     const Eigen::Vector3d& t2) {
  return filter::decide_distance(
      [&](double limit, bool limited, PairDistance& record) {
        return point_triangle_filter(p, t0, t1, t2, limit, limited, record);
      },
      [&] { return rational_point_triangle_distance(p, t0, t1, t2); });
}

}  // namespace clothcd::geometry
