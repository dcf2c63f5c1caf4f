#pragma once
/// @file
/// Exact support queries (largest projection on a direction) over a fixed point set, faster than a scan: the points are
/// grouped once, and a query scans only the groups whose bounding sphere could beat the best point found so far.

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// A point set (e.g. the convex-hull vertices of a rigid obstacle at rest) prepared for repeated support queries.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class SupportPoints {
 public:
  /// An empty set (every query returns -infinity).
  SupportPoints() = default;
  /// Groups the rows of `points` (#P x 3) by recursive median splits into groups of at most `group_size` points
  /// (0: about sqrt(#P)), each with a bounding sphere.
  explicit SupportPoints(const Vertices& points, int group_size = 0);

  /// max over the points p of direction . p, exactly the value a scan of every point gives (-infinity when empty).
  /// A group is skipped only when its sphere bound (centre . direction + radius * |direction|, the radius padded for
  /// round-off) does not exceed the best point already found, so the skipped points cannot hold the maximum.
  [[nodiscard]] double max_dot(const Eigen::Vector3d& direction) const;

  /// {min, max} over the points p of direction . p in one walk over the groups: exactly {-max_dot(-direction),
  /// max_dot(direction)} (negating the direction negates every product exactly), {+infinity, -infinity} when empty.
  /// Sets of at most kScanAll points are scanned whole, four points at a time, from clothcd::SimdLevel::Avx2 up.
  [[nodiscard]] std::pair<double, double> min_max_dot(const Eigen::Vector3d& direction) const;

  /// The most points min_max_dot scans whole instead of walking the groups.
  static constexpr int kScanAll = 1024;

  /// Number of points.
  [[nodiscard]] std::size_t size() const { return points_.size(); }

 private:
  [[nodiscard]] double group_bound(std::size_t g, const Eigen::Vector3d& direction, double length) const;
  [[nodiscard]] double group_max(std::size_t g, const Eigen::Vector3d& direction) const;
  // Widens [lo, hi] by the projections of group g's points.
  void group_min_max(std::size_t g, const Eigen::Vector3d& direction, double& lo, double& hi) const;

  std::vector<Eigen::Vector3d> points_;  // grouped: group g holds points_[begin_[g] .. begin_[g + 1])
  std::vector<int> begin_;
  std::vector<Eigen::Vector3d> centre_;
  std::vector<double> radius_;
  size_t scan_count_ = 0;            // points in coordinates_ (a multiple of 4; 0: no whole scan)
  std::vector<double> coordinates_;  // for a whole scan: all x, then all y, then all z, padded to scan_count_
};

}  // namespace clothcd::geometry
