// Support queries over sphere-bounded groups against a scan of every point: random, clustered and degenerate sets.
#include <catch2/catch.hpp>

#include <limits>
#include <random>

#include "clothcd/geometry/support_points.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

double scan_max(const Vertices& points, const Eigen::Vector3d& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.rows(); ++i) best = std::max(best, points.row(i).dot(d));
  return best;
}

void check_against_scan(const Vertices& points, std::mt19937_64& random, int group_size = 0) {
  const SupportPoints support(points, group_size);
  REQUIRE(support.size() == static_cast<size_t>(points.rows()));
  std::normal_distribution<double> n(0, 1);
  for (int q = 0; q < 200; ++q) {
    Eigen::Vector3d d(n(random), n(random), n(random));
    if (q < 6) d = (q % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(q / 2);  // the axes themselves: many ties on a grid
    if (q == 6) d = 1e-7 * d;                                          // tiny and huge directions
    if (q == 7) d = 1e7 * d;
    CAPTURE(q, d.transpose());
    REQUIRE(support.max_dot(d) == scan_max(points, d));  // the same point wins: bitwise equal
    const auto [low, high] = support.min_max_dot(d);
    REQUIRE(high == scan_max(points, d));
    REQUIRE(low == -scan_max(points, -d));
  }
}

}  // namespace

TEST_CASE("SupportPoints gives exactly the scan's maximum", "[geometry][obb][support]") {
  std::mt19937_64 random(7);
  std::normal_distribution<double> n(0, 1);
  for (int count : {1, 2, 3, 17, 500, 3000}) {
    CAPTURE(count);
    Vertices points(count, 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) << n(random), n(random), 100 + 3 * n(random);
    check_against_scan(points, random);
    check_against_scan(points, random, 1);
    // Points on a sphere: nearly every one is a support point of some direction.
    for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i).normalize();
    check_against_scan(points, random);
  }
}

TEST_CASE("SupportPoints on degenerate sets", "[geometry][obb][support]") {
  std::mt19937_64 random(11);
  std::uniform_int_distribution<int> cell(-3, 3);
  Vertices grid(400, 3), plane(400, 3), line(400, 3), same(50, 3);
  for (Eigen::Index i = 0; i < 400; ++i) {
    grid.row(i) << cell(random), cell(random), cell(random);  // many duplicates and ties
    plane.row(i) << cell(random), cell(random), 0.0;
    line.row(i) << 0.5 * cell(random), cell(random) * 1.0, 0.0;
    line(i, 1) = 2.0 * line(i, 0);
  }
  same.rowwise() = Eigen::RowVector3d(1.5, -2.0, 3.0);
  for (const Vertices* points : {&grid, &plane, &line, &same}) check_against_scan(*points, random);
  Vertices big_grid(3 * SupportPoints::kScanAll, 3);  // more than a whole scan takes: the group walk, with ties
  for (Eigen::Index i = 0; i < big_grid.rows(); ++i) big_grid.row(i) << cell(random), cell(random), cell(random);
  check_against_scan(big_grid, random);
  const SupportPoints empty{Vertices(0, 3)};
  CHECK(empty.max_dot(Eigen::Vector3d::UnitX()) == -std::numeric_limits<double>::infinity());
  const auto [low, high] = empty.min_max_dot(Eigen::Vector3d::UnitX());
  CHECK(low == std::numeric_limits<double>::infinity());
  CHECK(high == -std::numeric_limits<double>::infinity());
  CHECK(SupportPoints().size() == 0);
}
