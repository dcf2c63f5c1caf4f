// The triangle intersection test against the rational reference on seeded random pairs: generic pairs at scales
// from 1e-6 to 1e6 (near the origin and far from it), pairs on small integer grids (rich in coplanar, collinear,
// touching and degenerate configurations), pairs with a corner moved exactly onto the other's plane, edge or vertex
// and one ulp to either side, shared corners of every kind, and nearly flat neighbours (rounded into a tilted plane).
#include <catch2/catch.hpp>

#include <functional>

#include <Eigen/Geometry>

#include "geometry/triangle_pair_checks.hpp"

using namespace clothcd;
using namespace clothcd::test;

namespace {

using V = Eigen::Vector3d;

// Runs `count` pairs from `make` through the comparison; reports the first disagreement and how many there were.
void compare_all(int count, const std::function<void(Triangle&, Triangle&, SharedCorners&)>& make,
                 int* intersecting = nullptr) {
  int failures = 0, hits = 0;
  std::string first;
  for (int n = 0; n < count; ++n) {
    Triangle a, b;
    SharedCorners shared;
    make(a, b, shared);
    const std::string problem = disagreement(a, b, shared);
    if (!problem.empty() && failures++ == 0) first = problem;
    hits += geometry::exact_intersect_triangles(a, b, shared).intersect;
  }
  INFO(first);
  CHECK(failures == 0);
  if (intersecting) *intersecting = hits;
}

// Makes b share `count` random corners of a (b's corners in random slots); three makes a duplicated face.
SharedCorners share_random(std::mt19937_64& random, const Triangle& a, Triangle& b, int count) {
  std::array<int, 3> corners = {0, 1, 2}, slots = {0, 1, 2};
  std::shuffle(corners.begin(), corners.end(), random);
  std::shuffle(slots.begin(), slots.end(), random);
  std::array<int, 3> of_a = {-1, -1, -1};
  for (int k = 0; k < count; ++k) {
    of_a[slots[k]] = corners[k];
    b[slots[k]] = a[corners[k]];
  }
  return share(of_a);
}

// A corner of b in no pair.
int unshared_slot(const SharedCorners& shared) {
  bool used[3] = {false, false, false};
  for (int k = 0; k < shared.count; ++k) used[shared.pairs[k][1]] = true;
  return used[0] ? (used[1] ? 2 : 1) : 0;
}

// A point of a's plane at a + alpha (a1 - a0) + beta (a2 - a0), exact for grid corners and alpha, beta in eighths.
V on_plane(const Triangle& a, double alpha, double beta) {
  return a[0] + alpha * (a[1] - a[0]) + beta * (a[2] - a[0]);
}

}  // namespace

TEST_CASE("random pairs agree with the reference at every scale", "[geometry][triangle-intersection]") {
  for (const double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    for (const double offset : {0.0, 1e3}) {
      std::mt19937_64 random(static_cast<std::uint64_t>(std::log10(scale) * 7 + offset) + 11);
      const V center = offset * scale * V(1.0, -0.5, 0.25);
      int intersecting = 0;
      compare_all(
          1500,
          [&](Triangle& a, Triangle& b, SharedCorners&) {
            for (V& p : a) p = random_point(random, center, scale);
            const V other = random_point(random, center, scale);
            for (V& p : b) p = random_point(random, other, scale);
          },
          &intersecting);
      INFO("scale " << scale << ", offset " << offset);
      CHECK(intersecting > 100);  // both answers well represented
      CHECK(intersecting < 1400);
    }
  }
}

TEST_CASE("pairs on integer grids agree with the reference", "[geometry][triangle-intersection]") {
  for (const int exponent : {-20, 0, 20}) {
    for (const int range : {1, 2, 4}) {
      std::mt19937_64 random(1000 + 10 * exponent + range);
      std::uniform_int_distribution<int> shared_count(0, 3);
      const double unit = std::ldexp(1.0, exponent);
      compare_all(3000, [&](Triangle& a, Triangle& b, SharedCorners& shared) {
        for (V& p : a) p = unit * grid_point(random, range);
        for (V& p : b) p = unit * grid_point(random, range);
        // Mostly unshared, as most candidate pairs are.
        const int count = shared_count(random);
        shared = share_random(random, a, b, random() % 2 ? count : 0);
      });
    }
  }
}

TEST_CASE("corners moved onto the other face exactly and one ulp off agree with the reference",
          "[geometry][triangle-intersection]") {
  // alpha, beta in eighths: inside, on an edge, at a vertex, or outside in the plane.
  const std::array<std::array<double, 2>, 8> spots = {
      {{0.25, 0.25}, {0.5, 0.0}, {0.0, 0.625}, {0.5, 0.5}, {0.0, 0.0}, {1.0, 0.0}, {1.25, 0.125}, {-0.125, 0.5}}};
  for (const int exponent : {-20, 0, 20}) {
    for (const double offset : {0.0, 0x1p30}) {
      std::mt19937_64 random(2000 + exponent + (offset > 0));
      std::uniform_int_distribution<int> pick(0, 7), axis(0, 2), step(-1, 1), shared_count(0, 2);
      const double unit = std::ldexp(1.0, exponent);
      compare_all(4000, [&](Triangle& a, Triangle& b, SharedCorners& shared) {
        for (V& p : a) p = unit * (grid_point(random, 1 << 20) + V::Constant(offset));
        for (V& p : b) p = unit * (grid_point(random, 1 << 20) + V::Constant(offset));
        const int count = shared_count(random);
        shared = share_random(random, a, b, count);
        // One unshared corner of b onto a's plane, then possibly one ulp off it.
        const int j = unshared_slot(shared);
        const auto& spot = spots[pick(random)];
        b[j] = on_plane(a, spot[0], spot[1]);
        const int direction = step(random);
        if (direction != 0) b[j] = ulp_step(b[j], axis(random), direction > 0);
        // Sometimes a second corner of b onto the plane too: an edge of b in a's plane.
        if (count == 0 && random() % 4 == 0) {
          const auto& second = spots[pick(random)];
          b[(j + 1) % 3] = on_plane(a, second[0], second[1]);
        }
      });
    }
  }
}

TEST_CASE("nearly flat neighbours agree with the reference", "[geometry][triangle-intersection]") {
  // A small patch of a grid rounded into a tilted plane: neighbouring faces are coplanar up to rounding, the case
  // where the filter cannot decide and the fallback answers.
  std::mt19937_64 random(3000);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  compare_all(3000, [&](Triangle& a, Triangle& b, SharedCorners& shared) {
    const V u = V(unit(random), unit(random), unit(random)).normalized();
    const V v = u.cross(V(unit(random), unit(random), unit(random))).normalized();
    const V origin = V(unit(random), unit(random), unit(random)) * 10.0;
    const auto at = [&](double x, double y) -> V { return origin + x * u + y * v; };
    a = {at(0, 0), at(1, 0), at(0, 1)};
    switch (random() % 3) {
      case 0:  // the edge neighbour
        b = {at(1, 0), at(1, 1), at(0, 1)};
        shared = share({1, -1, 2});
        break;
      case 1:  // a vertex neighbour
        b = {at(1, 0), at(2, 0), at(1, -1)};
        shared = share({1, -1, -1});
        break;
      default:  // folded onto a, or overlapping it without shared corners
        b = {at(1, 0), at(0, 1), at(0.25, 0.25)};
        shared = random() % 2 ? share({1, 2, -1}) : SharedCorners{};
        break;
    }
  });
}

TEST_CASE("degenerate triangles agree with the reference", "[geometry][triangle-intersection]") {
  std::mt19937_64 random(4000);
  std::uniform_int_distribution<int> multiple(-2, 3), shared_count(0, 2);
  const auto degenerate = [&](Triangle& t) {
    const V p = grid_point(random, 2), d = grid_point(random, 1);
    t = {p, p + multiple(random) * d, p + multiple(random) * d};
    std::shuffle(t.begin(), t.end(), random);
  };
  compare_all(4000, [&](Triangle& a, Triangle& b, SharedCorners& shared) {
    degenerate(b);
    if (random() % 2) {
      degenerate(a);
    } else {
      for (V& p : a) p = grid_point(random, 2);
    }
    shared = share_random(random, a, b, shared_count(random));
  });
}
