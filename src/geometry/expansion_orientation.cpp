// The orientation determinants on floating-point expansions: the differences exactly (one component when the rounded
// difference is exact, as it mostly is for nearby points, else two), then the cofactor expansion in exact products
// and sums, whose largest component has the determinant's sign.
#include "geometry/expansion_orientation.hpp"

#include <cmath>

#include "geometry/expansion.hpp"

namespace clothcd::geometry::detail {

namespace {

bool in_range(double x) {
  const double magnitude = std::abs(x);
  return magnitude == 0.0 || (magnitude >= kExpansionSmallest && magnitude <= kExpansionLargest);
}

bool in_range(const Eigen::Vector3d& p) {
  return in_range(p[0]) && in_range(p[1]) && in_range(p[2]);
}

}  // namespace

std::optional<int> expansion_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                      const Eigen::Vector3d& s) {
  if (!in_range(p) || !in_range(q) || !in_range(r) || !in_range(s)) return std::nullopt;
  Expansion x1[3], x2[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x1[k] = Expansion::difference(q[k], p[k]);
    x2[k] = Expansion::difference(r[k], p[k]);
    y[k] = Expansion::difference(s[k], p[k]);
  }
  // Each difference has at most 2 components, each cross-product component at most 16 and each of its products with
  // y at most 64: only the two final sums can outgrow the capacity (a value of very scattered bits).
  try {
    Expansion det = y[0] * (x1[1] * x2[2] - x1[2] * x2[1]);
    det += y[1] * (x1[2] * x2[0] - x1[0] * x2[2]);
    det += y[2] * (x1[0] * x2[1] - x1[1] * x2[0]);
    return det.sign();
  } catch (const ExpansionCapacityExceeded&) {
    return std::nullopt;
  }
}

std::optional<int> expansion_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                                      int drop_axis) {
  const int i = (drop_axis + 1) % 3, j = (drop_axis + 2) % 3;
  if (!in_range(p[i]) || !in_range(p[j]) || !in_range(q[i]) || !in_range(q[j]) || !in_range(r[i]) || !in_range(r[j])) {
    return std::nullopt;
  }
  // At most 2 components per difference, 8 per product, 16 in all: within the capacity.
  const Expansion ei = Expansion::difference(q[i], p[i]), ej = Expansion::difference(q[j], p[j]);
  const Expansion fi = Expansion::difference(r[i], p[i]), fj = Expansion::difference(r[j], p[j]);
  return (ei * fj - ej * fi).sign();
}

}  // namespace clothcd::geometry::detail
