// The slab extremes of eqs. 15-16: the branch-free version gives exactly the rows of the plain scan (random, grid,
// flat and repeated points, every slab count), and the scan's rows are the first maximum of each slab.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "geometry/slab_extremes.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

constexpr int kSlabCounts[] = {-3, 0, 1, 2, 7, 16, 64, 256, 1000};

std::vector<int> fast_rows(const Vertices& points, const Eigen::Vector3d& centre, int slabs) {
  std::vector<int> rows(3 * detail::kMaxSlabs * detail::kSlabValues + 1, -7);  // + 1: a guard entry
  detail::slab_extremes(points, centre, slabs, rows.data());
  return rows;
}

std::vector<int> reference_rows(const Vertices& points, const Eigen::Vector3d& centre, int slabs) {
  std::vector<int> rows(3 * detail::kMaxSlabs * detail::kSlabValues + 1, -7);  // + 1: a guard entry
  detail::slab_extremes_reference(points, centre, slabs, rows.data());
  return rows;
}

// Every row the reference names holds its slab's largest value, no earlier row of the slab has it, and a slab is
// empty (-1) exactly when no point falls in it.
void check_reference_semantics(const Vertices& points, const Eigen::Vector3d& centre, int slabs) {
  const int s = std::clamp(slabs, 1, detail::kMaxSlabs);
  const std::vector<int> rows = reference_rows(points, centre, slabs);
  const Eigen::Vector3d lo = points.colwise().minCoeff().transpose(), hi = points.colwise().maxCoeff().transpose();
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    std::vector<std::vector<int>> members(static_cast<size_t>(s));
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const double width = hi[a] > lo[a] ? s / (hi[a] - lo[a]) : 0.0;
      members[size_t(std::min(s - 1, static_cast<int>((points(i, a) - lo[a]) * width)))].push_back(int(i));
    }
    for (int slab = 0; slab < s; ++slab) {
      for (int k = 0; k < detail::kSlabValues; ++k) {
        const auto value = [&](int i) {
          const Eigen::Vector3d p = points.row(i).transpose();
          const double values[] = {(p - centre).squaredNorm(), p[b], -p[b], p[c], -p[c]};
          return values[k];
        };
        const int row = rows[size_t((a * s + slab) * detail::kSlabValues + k)];
        CAPTURE(a, slab, k, row);
        if (members[size_t(slab)].empty()) {
          REQUIRE(row == -1);
          continue;
        }
        int first = members[size_t(slab)].front();
        for (int i : members[size_t(slab)]) first = value(i) > value(first) ? i : first;
        REQUIRE(row == first);
      }
    }
  }
}

void check(const Vertices& points, const Eigen::Vector3d& centre) {
  for (int slabs : kSlabCounts) {
    CAPTURE(points.rows(), slabs);
    const int entries = 3 * std::clamp(slabs, 1, detail::kMaxSlabs) * detail::kSlabValues;
    const std::vector<int> fast = fast_rows(points, centre, slabs), reference = reference_rows(points, centre, slabs);
    REQUIRE(std::equal(fast.begin(), fast.begin() + entries, reference.begin()));
    REQUIRE(fast[size_t(entries)] == -7);  // nothing written past the slabs in use
    if (points.rows() <= 300 && slabs <= 64) check_reference_semantics(points, centre, slabs);
  }
}

}  // namespace

TEST_CASE("Slab extremes: the branch-free version matches the scan on random points", "[geometry][obb][slab]") {
  std::mt19937_64 random(11);
  std::normal_distribution<double> n(0, 1);
  for (int count : {1, 2, 3, 5, 64, 65, 129, 300, 2000}) {
    Vertices points(count, 3);
    for (int i = 0; i < count; ++i) points.row(i) << n(random), 3 * n(random), 0.1 * n(random);
    check(points, Eigen::Vector3d(n(random), n(random), n(random)));
    check(1e6 * points, Eigen::Vector3d::Zero());
    check(1e-6 * points, Eigen::Vector3d::Constant(1.0));
  }
}

TEST_CASE("Slab extremes on degenerate points: ties, flat axes, repeats", "[geometry][obb][slab]") {
  std::mt19937_64 random(12);
  std::uniform_int_distribution<int> cell(-3, 3);
  Vertices grid(200, 3);  // many equal coordinates and distances: the first row must win every tie
  for (int i = 0; i < 200; ++i) grid.row(i) << cell(random), cell(random), cell(random);
  check(grid, Eigen::Vector3d::Zero());
  check(grid, Eigen::Vector3d(0.5, 0, 0));
  Vertices flat = grid;
  flat.col(2).setConstant(4.0);  // one flat axis: a single slab
  check(flat, Eigen::Vector3d::Zero());
  Vertices line = Vertices::Zero(50, 3);
  for (int i = 0; i < 50; ++i) line(i, 0) = i % 7;
  check(line, Eigen::Vector3d::Zero());
  check(Vertices::Constant(33, 3, -2.5), Eigen::Vector3d::Zero());  // every point the same
  Vertices zeros(40, 3);  // +0 and -0: equal coordinates of different signs
  for (int i = 0; i < 40; ++i) zeros.row(i) << (i % 2 ? -0.0 : 0.0), (i % 3 ? 0.0 : -0.0), cell(random) * 0.0;
  check(zeros, Eigen::Vector3d::Zero());
  zeros(17, 0) = 1.0;
  check(zeros, Eigen::Vector3d::Zero());
  Vertices repeated(100, 3);
  for (int i = 0; i < 100; ++i) repeated.row(i) = grid.row(i % 10);
  check(repeated, Eigen::Vector3d::Ones());
}
