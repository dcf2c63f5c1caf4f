// Minimum-area enclosing rectangle: H. Freeman and R. Shapira, "Determining the minimum-area encasing rectangle for an
// arbitrary closed curve", CACM 1975 (a side lies on a hull edge); G. Toussaint, "Solving geometric problems with the
// rotating calipers", 1983 (the other extremes advance monotonically). Hull by A. M. Andrew's monotone chain, 1979.
#include "min_area_rectangle.hpp"

#include <algorithm>
#include <limits>

namespace clothcd::geometry::detail {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

void convex_hull(std::vector<Eigen::Vector2d>& points, std::vector<Eigen::Vector2d>& hull) {
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  hull.resize(2 * points.size() + 1);
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
}

}  // namespace

Rectangle min_area_rectangle(std::vector<Eigen::Vector2d>& points, std::vector<Eigen::Vector2d>& hull) {
  Rectangle best;
  if (points.size() < 3) return best;
  convex_hull(points, hull);
  const size_t n = hull.size();
  if (n < 3) return best;
  best.area = std::numeric_limits<double>::infinity();
  // Calipers: `right` is the farthest point along the edge, `top` the farthest from the edge's line, `left` the
  // farthest against the edge direction. Each only moves forward as the edge turns counter-clockwise, so each climbs
  // from its previous position (at most n steps, which also ends plateaus).
  size_t right = 1, top = 1, left = 1;
  auto climb = [&hull, n](size_t& index, auto&& score) {
    for (size_t step = 0; step < n && score(hull[(index + 1) % n]) >= score(hull[index]); ++step) index = (index + 1) % n;
  };
  for (size_t e = 0; e < n; ++e) {
    const Eigen::Vector2d& a = hull[e];
    Eigen::Vector2d d = hull[(e + 1) % n] - a;
    const double length = d.norm();
    if (length == 0) continue;
    d /= length;
    const Eigen::Vector2d up(-d.y(), d.x());
    const auto along = [&d](const Eigen::Vector2d& p) { return p.dot(d); };
    const auto against = [&d](const Eigen::Vector2d& p) { return -p.dot(d); };
    const auto height = [&a, &up](const Eigen::Vector2d& p) { return (p - a).dot(up); };
    if (e == 0) right = 1;
    climb(right, along);
    if (e == 0) top = right;
    climb(top, height);
    if (e == 0) left = top;
    climb(left, against);
    const double width = (hull[right] - hull[left]).dot(d);
    const double h = (hull[top] - a).dot(up);
    if (width * h < best.area) best = {width * h, d};
  }
  return best;
}

}  // namespace clothcd::geometry::detail
