#pragma once
// Private: minimum-area enclosing rectangle of 2-D points (convex hull + rotating calipers).

#include <vector>

#include <Eigen/Dense>

namespace clothcd::geometry::detail {

/// A rectangle: its area and the unit direction of one side (the other side is perpendicular).
struct Rectangle {
  double area = 0.0;                                 ///< Area (0 for fewer than 3 non-collinear points).
  Eigen::Vector2d side = Eigen::Vector2d::UnitX();  ///< Unit direction of one side.
};

/// The minimum-area rectangle enclosing `points` (reordered in place). Some side of it lies on a hull edge (Freeman &
/// Shapira 1975), so every hull edge is tried, with rotating calipers for the three other extremes: O(n log n) in all.
/// `hull` is a reusable buffer (it receives the counter-clockwise convex hull).
[[nodiscard]] Rectangle min_area_rectangle(std::vector<Eigen::Vector2d>& points, std::vector<Eigen::Vector2d>& hull);

}  // namespace clothcd::geometry::detail
