#pragma once
// The measures of a candidate pair that the culling filters and the pair network's features share: the projection
// filter's five fixed directions (Wan et al., eq. 10), the point pairs whose projected gaps it compares (eqs. 8-9),
// the Bernstein coefficients of the coplanarity cubic (eqs. 6-7) and the filters' signed margins. The computations
// are templates over the vector type, written once: one pair (Eigen::Vector3d, double) and a lane group of pairs (the
// library's lane vectors, one pair per lane) run the same IEEE operations in the same order, so their values agree bit
// for bit.
#include <array>
#include <type_traits>

#include <Eigen/Dense>

#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd::ccd::pair_measures {

/// One of eq. (10)'s fixed directions of the projection filter.
struct ProjectionDirection {
  std::array<double, 3> s;     ///< The direction unnormalised: components 0 or 1.
  double norm;                 ///< |s| rounded (1, sqrt 2 or sqrt 3).
  double l1;                   ///< |s|_1, the count of its unit components.
  std::array<double, 3> unit;  ///< s / |s| by components, each rounded from sqrt(1/2) or sqrt(1/3).
};

/// Eq. (10)'s five directions, (1,0,0), (1,1,0), (1,0,1), (0,1,1), (1,1,1), in the order the filters try them. The
/// literals are the correctly rounded square roots (std::sqrt(2.0), std::sqrt(3.0), std::sqrt(0.5),
/// std::sqrt(1.0 / 3.0)), so that the table is a constant of the compiler.
inline constexpr std::array<ProjectionDirection, 5> kProjectionDirections{{
    {{1.0, 0.0, 0.0}, 1.0, 1.0, {1.0, 0.0, 0.0}},
    {{1.0, 1.0, 0.0}, 0x1.6a09e667f3bcdp+0, 2.0, {0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bcdp-1, 0.0}},
    {{1.0, 0.0, 1.0}, 0x1.6a09e667f3bcdp+0, 2.0, {0x1.6a09e667f3bcdp-1, 0.0, 0x1.6a09e667f3bcdp-1}},
    {{0.0, 1.0, 1.0}, 0x1.6a09e667f3bcdp+0, 2.0, {0.0, 0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bcdp-1}},
    {{1.0, 1.0, 1.0}, 0x1.bb67ae8584caap+0, 3.0, {0x1.279a74590331cp-1, 0x1.279a74590331cp-1, 0x1.279a74590331cp-1}},
}};

/// The point pairs (a point of the first primitive, a point of the second) whose differences the projection filter
/// projects, four per kind (index static_cast<int>(kind)): vertex-face x0 - x1, x0 - x2, x0 - x3 and x0 - x3 once more
/// (eq. 8; a repeated gap changes neither extreme), edge-edge x0 - x2, x0 - x3, x1 - x2, x1 - x3 (eq. 9).
inline constexpr int kGapPoints[2][4][2] = {{{0, 1}, {0, 2}, {0, 3}, {0, 3}}, {{0, 2}, {0, 3}, {1, 2}, {1, 3}}};

/// a x b (Eigen's), so that the templates below read the same for one pair and for lanes.
inline Eigen::Vector3d cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.cross(b); }

/// a . b (Eigen's: (a0 b0 + a1 b1) + a2 b2).
inline double dot(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.dot(b); }

/// One pair as one lane: std::min(a, b) (b < a ? b : a).
inline double lane_min(double a, double b) { return b < a ? b : a; }

/// One pair as one lane: std::max(a, b) (a < b ? b : a).
inline double lane_max(double a, double b) { return a < b ? b : a; }

/// The Bernstein coefficients on [0, 1] of the coplanarity cubic D(t) = (x1 - x0)(t) x (x2 - x0)(t) . (x3 - x0)(t)
/// (eqs. 6-7; x_k(t) linear from start[k] to end[k]), from its power-basis coefficients c0..c3: c0,
/// c0 + c1 / 3, c0 + (2 c1 + c2) / 3, c0 + c1 + c2 + c3. D lies in their convex hull, so four of one strict sign mean
/// no coplanarity. V is Eigen::Vector3d (one pair) or a lane vector (one pair per lane).
template <class V>
[[gnu::always_inline]] inline auto coplanarity_bernstein(const V* start, const V* end) {
  const V a1 = start[1] - start[0], a2 = start[2] - start[0], a3 = start[3] - start[0];
  const V v1 = (end[1] - end[0]) - a1, v2 = (end[2] - end[0]) - a2, v3 = (end[3] - end[0]) - a3;
  const auto c0 = dot(cross(a1, a2), a3);
  const auto c1 = dot(cross(v1, a2), a3) + dot(cross(a1, v2), a3) + dot(cross(a1, a2), v3);
  const auto c2 = dot(cross(v1, v2), a3) + dot(cross(v1, a2), v3) + dot(cross(a1, v2), v3);
  const auto c3 = dot(cross(v1, v2), v3);
  using Value = std::decay_t<decltype(c0)>;
  return std::array<Value, 4>{c0, c0 + c1 / 3.0, c0 + (2.0 * c1 + c2) / 3.0, c0 + c1 + c2 + c3};
}

/// The signed margin of "all of values[0, count) have one strict sign": the smallest when all are positive, minus the
/// largest when all are negative, else <= 0 (the first smallest and the last largest of equal values).
template <class T>
[[gnu::always_inline]] inline T same_sign_margin(const T* values, int count) {
  T lo = values[0], hi = values[0];
  for (int k = 1; k < count; ++k) {
    lo = lane_min(lo, values[k]);
    hi = lane_max(values[k], hi);
  }
  return lane_max(lo, -hi);
}

/// The projection filter's margin along direction s: same_sign_margin of the projected gaps s . gap[t][j] at both
/// times (gap[t][j] = the difference of kGapPoints[kind][j] at time t), positive exactly when the projections of the
/// two primitives stay apart along s over the whole step. S is an Eigen::Vector3d or a pointer to three components.
template <class V, class S>
[[gnu::always_inline]] inline auto projection_margin(const V (&gap)[2][4], const S& s) {
  decltype(dot(gap[0][0], s)) gaps[8];
  for (int t = 0; t < 2; ++t)
    for (int j = 0; j < 4; ++j) gaps[4 * t + j] = dot(gap[t][j], s);
  return same_sign_margin(gaps, 8);
}

}  // namespace clothcd::ccd::pair_measures
