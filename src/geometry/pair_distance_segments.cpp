// The edge-edge filter of the pair distances. After three cheap certain rejections (a box axis, a separating direction
// from approximate closest points, the distance of the two lines) the cell of the closest pair is certified on the parameter square of F(s, u) = |a0 + s da - b0 - u db|^2,
// a convex function, by the strict Karush-Kuhn-Tucker conditions of one cell: at a corner both partial derivatives
// point strictly inwards, on a side the free parameter is strictly inside (0, 1) and the other derivative points
// strictly inwards, inside both parameters are strictly inside. Strictly satisfied conditions make that parameter pair
// the only closest pair, so the type is exact. With n = da x db, w = b0 - a0, the free parameters are s = S0 / |n|^2,
// u = U0 / |n|^2 with S0 = (w x db) . n and U0 = (w x da) . n (and |n|^2 - S0 = ((a1 - b0) x db) . n, |n|^2 - U0 =
// ((a0 - b1) x da) . n, written on direct differences of the inputs for accuracy near the ends).
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

// Some axis separates the boxes of the two segments by more than d.
bool box_apart(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
               const Eigen::Vector3d& b1, double d) {
  for (int axis = 0; axis < 3; ++axis) {
    const double a_lo = std::min(a0[axis], a1[axis]), a_hi = std::max(a0[axis], a1[axis]);
    const double b_lo = std::min(b0[axis], b1[axis]), b_hi = std::max(b0[axis], b1[axis]);
    if (filter::gap_exceeds(b_lo, a_hi, d) || filter::gap_exceeds(a_lo, b_hi, d)) return true;
  }
  return false;
}

DistanceType offset(DistanceType first, int k) {
  return static_cast<DistanceType>(static_cast<int>(first) + k);
}

// The cell's squared distance num / den against d, then the record: the distance when `accurate` (the lengths whose
// squares num and den are were certified), and the rest from `fill` (parameters, direction; a parameter strictly inside
// (0, 1) may round to just above 1, hence the clamps).
template <int KN, int KD, typename Fill>
Outcome finish(const Bounded<KN>& num, const Bounded<KD>& den, double d, bool limited, bool accurate, DistanceType type,
               PairDistance& out, Fill fill) {
  if (limited) {
    const int within = filter::within_sign(num, den, d);
    if (within < 0) return Outcome::Apart;
    if (within == 0) return Outcome::Undecided;
  }
  if (!accurate) return Outcome::Undecided;
  out.distance = filter::distance_from_squares(num.value, den.value);
  fill();
  out.type = type;
  return Outcome::Found;
}

Outcome segment_segment_filter(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                               const Eigen::Vector3d& b1, double d, bool limited, PairDistance& out) {
  if (!filter::in_range({&a0, &a1, &b0, &b1})) return Outcome::Undecided;
  if (limited && box_apart(a0, a1, b0, b1, d)) return Outcome::Apart;
  // x[i][j] = a_i - b_j.
  const std::array<std::array<BoundedVector<1>, 2>, 2> x{
      {{difference(a0, b0), difference(a0, b1)}, {difference(a1, b0), difference(a1, b1)}}};
  if (limited) {
    if (filter::separated_along(segment_segment_offset(a0, a1, b0, b1), d, x[0][0], x[0][1], x[1][0], x[1][1]))
      return Outcome::Apart;
  }
  const BoundedVector<1> da = difference(a1, a0), db = difference(b1, b0), w = difference(b0, a0);
  const BoundedVector<4> n = cross(da, db);
  const Bounded<8> height = dot(w, n);
  const Bounded<11> cross_squared = dot(n, n);
  // The lines' distance |height| / |n| is at most the segments'.
  const int lines_within = limited ? filter::within_sign(height * height, cross_squared, d) : 0;
  if (lines_within < 0) return Outcome::Apart;

  const Bounded<11> s0 = dot(cross(w, db), n), s1 = dot(cross(x[1][0], db), n);
  const Bounded<11> u0 = dot(cross(w, da), n), u1 = dot(cross(x[0][1], da), n);
  const std::array<int, 2> s_inside{sign(s0), sign(s1)}, u_inside{sign(u0), sign(u1)};
  if (s_inside[0] > 0 && s_inside[1] > 0 && u_inside[0] > 0 && u_inside[1] > 0) {
    if (limited && lines_within == 0) return Outcome::Undecided;
    const bool accurate = bounded::accurate_length<filter::kNumeratorBits>(height) &&
                          bounded::accurate_length<filter::kDenominatorBits>(n, cross_squared.value);
    return finish(height * height, cross_squared, d, false, accurate, DistanceType::EdgeEdge, out, [&] {
      out.parameters = {std::min(s0.value / cross_squared.value, 1.0), std::min(u0.value / cross_squared.value, 1.0)};
      out.direction = (height.value > 0.0 ? Eigen::Vector3d(-n.value) : n.value).normalized();
    });
  }
  // along_a[i][j] = da . x_ij, along_b[i][j] = db . x_ij: the partial derivatives of F at the corners (up to 2, -2).
  std::array<std::array<int, 2>, 2> along_a, along_b;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      along_a[i][j] = sign(dot(da, x[i][j]));
      along_b[i][j] = sign(dot(db, x[i][j]));
    }
  }
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (along_a[i][j] == (i == 0 ? 1 : -1) && along_b[i][j] == (j == 0 ? -1 : 1)) {
        const Bounded<5> squared = dot(x[i][j], x[i][j]);
        return finish(squared, bounded::exact(1.0), d, limited,
                      bounded::accurate_length<filter::kNumeratorBits>(x[i][j], squared.value),
                      offset(DistanceType::VertexA0VertexB0, 2 * i + j), out, [&] {
                        out.parameters = {static_cast<double>(i), static_cast<double>(j)};
                        out.direction = x[i][j].value.normalized();
                      });
      }
    }
  }
  // Side s = i: a_i projects strictly inside b, and S_i < 0 (F's s-derivative points inwards there).
  for (int i = 0; i < 2; ++i) {
    if (along_b[i][0] > 0 && along_b[i][1] < 0 && s_inside[i] < 0) {
      const BoundedVector<4> c = cross(db, x[i][0]);
      const Bounded<11> squared_area = dot(c, c);
      const Bounded<5> length_squared = dot(db, db);
      const bool accurate = bounded::accurate_length<filter::kNumeratorBits>(c, squared_area.value) &&
                            bounded::accurate_length<filter::kDenominatorBits>(db, length_squared.value);
      return finish(
          squared_area, length_squared, d, limited, accurate, offset(DistanceType::VertexA0Edge, i), out, [&] {
            out.parameters = {static_cast<double>(i), std::min(dot(db, x[i][0]).value / length_squared.value, 1.0)};
            out.direction = c.value.cross(db.value).normalized();
          });
    }
  }
  // Side u = j: b_j projects strictly inside a, and U_j < 0.
  for (int j = 0; j < 2; ++j) {
    if (along_a[0][j] < 0 && along_a[1][j] > 0 && u_inside[j] < 0) {
      const BoundedVector<4> c = cross(da, x[0][j]);
      const Bounded<11> squared_area = dot(c, c);
      const Bounded<5> length_squared = dot(da, da);
      const bool accurate = bounded::accurate_length<filter::kNumeratorBits>(c, squared_area.value) &&
                            bounded::accurate_length<filter::kDenominatorBits>(da, length_squared.value);
      return finish(
          squared_area, length_squared, d, limited, accurate, offset(DistanceType::EdgeVertexB0, j), out, [&] {
            out.parameters = {std::min(-dot(da, x[0][j]).value / length_squared.value, 1.0), static_cast<double>(j)};
            out.direction = c.value.cross(da.value).normalized();
          });
    }
  }
  return Outcome::Undecided;
}

}  // namespace

bool segment_segment_within(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                            const Eigen::Vector3d& b1, double d, PairDistance& out) {
  return filter::decide_within(
      d, out,
      [&](double limit, bool limited, PairDistance& record) {
        return segment_segment_filter(a0, a1, b0, b1, limit, limited, record);
      },
      [&] { return rational_segment_segment_distance(a0, a1, b0, b1); });
}

PairDistance segment_segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                                      const Eigen::Vector3d& b1) {
  return filter::decide_distance(
      [&](double limit, bool limited, PairDistance& record) {
        return segment_segment_filter(a0, a1, b0, b1, limit, limited, record);
      },
      [&] { return rational_segment_segment_distance(a0, a1, b0, b1); });
}

}  // namespace clothcd::geometry
