// Support queries over a fixed point set by branch and bound over sphere-bounded groups (see support_points.hpp).
#include "clothcd/geometry/support_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/simd.hpp"
#include "support/simd_level.hpp"


namespace clothcd::geometry {
namespace {

// Splits points[begin, end) at the median of their widest coordinate until every part has at most `group_size`
// points; appends each part's start to `starts`.
void split(std::vector<Eigen::Vector3d>& points, int begin, int end, int group_size, std::vector<int>& starts) {
  if (end - begin <= group_size) {
    starts.push_back(begin);
    return;
  }
  Eigen::Vector3d lo = points[size_t(begin)], hi = lo;
  for (int i = begin; i < end; ++i) {
    lo = lo.cwiseMin(points[size_t(i)]);
    hi = hi.cwiseMax(points[size_t(i)]);
  }
  Eigen::Index axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(points.begin() + begin, points.begin() + middle, points.begin() + end,
                   [axis](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a[axis] < b[axis]; });
  split(points, begin, middle, group_size, starts);
  split(points, middle, end, group_size, starts);
}

// The wide kernel: the scan of every point on four double lanes.
#define CLOTHCD_SIMD_KERNEL "geometry/support_points_lanes.hpp"
#define CLOTHCD_SIMD_KERNEL_WIDE
#include "support/simd_versions.hpp"

}  // namespace

SupportPoints::SupportPoints(const Vertices& points, int group_size) {
  const auto n = static_cast<int>(points.rows());
  if (n == 0) return;
  if (group_size <= 0) group_size = std::max(4, static_cast<int>(std::sqrt(double(n))));
  points_.resize(size_t(n));
  for (int i = 0; i < n; ++i) points_[size_t(i)] = points.row(i).transpose();
  split(points_, 0, n, group_size, begin_);
  begin_.push_back(n);
  for (size_t g = 0; g + 1 < begin_.size(); ++g) {
    Eigen::Vector3d lo = points_[size_t(begin_[g])], hi = lo;
    for (int i = begin_[g]; i < begin_[g + 1]; ++i) {
      lo = lo.cwiseMin(points_[size_t(i)]);
      hi = hi.cwiseMax(points_[size_t(i)]);
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    double radius = 0;
    for (int i = begin_[g]; i < begin_[g + 1]; ++i) radius = std::max(radius, (points_[size_t(i)] - centre).norm());
    // Padding far above the round-off of a dot product, so a computed bound never falls below a computed p . d.
    centre_.push_back(centre);
    radius_.push_back(radius + 1e-9 * (centre.norm() + radius));
  }
  // Few points: a scan of them all, four at a time, costs less than the group bounds and the branches on them.
  if (n <= kScanAll && simd_level() >= SimdLevel::Avx2) {
    scan_count_ = (size_t(n) + 3) / 4 * 4;
    coordinates_.resize(3 * scan_count_);
    for (size_t i = 0; i < scan_count_; ++i)  // padded with copies of the first point (min and max unchanged)
      for (int k = 0; k < 3; ++k) coordinates_[k * scan_count_ + i] = points_[i < size_t(n) ? i : 0][k];
  }
}

double SupportPoints::group_bound(std::size_t g, const Eigen::Vector3d& direction, double length) const {
  return centre_[g].dot(direction) + radius_[g] * length;
}

double SupportPoints::group_max(std::size_t g, const Eigen::Vector3d& direction) const {
  double best = -std::numeric_limits<double>::infinity();
  for (int i = begin_[g]; i < begin_[g + 1]; ++i) best = std::max(best, points_[size_t(i)].dot(direction));
  return best;
}

double SupportPoints::max_dot(const Eigen::Vector3d& direction) const {
  const size_t groups = centre_.size();
  if (groups == 0) return -std::numeric_limits<double>::infinity();
  const double length = direction.norm();
  // Scan the most promising group first, so the bound prunes as much as possible; then every group that may beat it.
  size_t first = 0;
  double first_bound = group_bound(0, direction, length);
  for (size_t g = 1; g < groups; ++g) {
    const double bound = group_bound(g, direction, length);
    if (bound > first_bound) first_bound = bound, first = g;
  }
  double best = group_max(first, direction);
  for (size_t g = 0; g < groups; ++g) {
    if (g != first && group_bound(g, direction, length) > best) best = std::max(best, group_max(g, direction));
  }
  return best;
}

void SupportPoints::group_min_max(std::size_t g, const Eigen::Vector3d& direction, double& lo, double& hi) const {
  for (int i = begin_[g]; i < begin_[g + 1]; ++i) {
    const double d = points_[size_t(i)].dot(direction);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
}

std::pair<double, double> SupportPoints::min_max_dot(const Eigen::Vector3d& direction) const {
  if (scan_count_ > 0) {  // only where the CPU runs AVX2 (see the constructor): never off x86-64
    return CLOTHCD_SIMD_DISPATCH_WIDE(SimdLevel::Avx2, scan_min_max(coordinates_.data(), scan_count_, direction),
                                      std::make_pair(0.0, 0.0));
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const size_t groups = centre_.size();
  if (groups == 0) return {lo, hi};
  const double length = direction.norm();
  // As max_dot, for both ends at once: the group whose sphere reaches farthest each way first, then every group whose
  // sphere may reach beyond either end found so far (a group's sphere spans centre . direction -+ radius |direction|).
  size_t first_lo = 0, first_hi = 0;
  double best_lo = std::numeric_limits<double>::infinity(), best_hi = -best_lo;
  for (size_t g = 0; g < groups; ++g) {
    const double c = centre_[g].dot(direction), r = radius_[g] * length;
    if (c - r < best_lo) best_lo = c - r, first_lo = g;
    if (c + r > best_hi) best_hi = c + r, first_hi = g;
  }
  group_min_max(first_lo, direction, lo, hi);
  if (first_hi != first_lo) group_min_max(first_hi, direction, lo, hi);
  for (size_t g = 0; g < groups; ++g) {
    if (g == first_lo || g == first_hi) continue;
    const double c = centre_[g].dot(direction), r = radius_[g] * length;
    if (c - r < lo || c + r > hi) group_min_max(g, direction, lo, hi);
  }
  return {lo, hi};
}

}  // namespace clothcd::geometry
