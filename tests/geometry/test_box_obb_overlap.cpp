// The AABB-OBB separating axis test: on axis-aligned OBBs it agrees with the box test wherever the boxes are not
// within rounding of touching; on turned OBBs it reports every overlap a shared point shows and every separation a
// plane between their corners shows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "clothcd/geometry/bounding_volumes.hpp"
#include "geometry/box_obb_overlap.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

struct Box {
  double min[3];
  double max[3];
};

Box random_box(std::mt19937& rng) {
  std::uniform_real_distribution<double> centre(-2.0, 2.0), half(0.01, 1.0);
  Box b{};
  for (int k = 0; k < 3; ++k) {
    const double c = centre(rng), h = half(rng);
    b.min[k] = c - h;
    b.max[k] = c + h;
  }
  return b;
}

Obb random_obb(std::mt19937& rng, bool turned) {
  std::uniform_real_distribution<double> centre(-2.0, 2.0), half(0.01, 1.0), angle(-3.0, 3.0);
  Obb o;
  o.center = Eigen::Vector3d(centre(rng), centre(rng), centre(rng));
  o.half_extents = Eigen::Vector3d(half(rng), half(rng), half(rng));
  if (turned) {
    o.axes = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()))
                 .toRotationMatrix();
  }
  return o;
}

// The eight corners of `o`.
std::array<Eigen::Vector3d, 8> corners(const Obb& o) {
  std::array<Eigen::Vector3d, 8> c;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d s((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    c[i] = o.center + o.axes * s.cwiseProduct(o.half_extents);
  }
  return c;
}

bool box_contains(const Box& b, const Eigen::Vector3d& p) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] < b.min[k] || p[k] > b.max[k]) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("the AABB-OBB test agrees with the box test on axis-aligned OBBs", "[geometry][obb-overlap]") {
  std::mt19937 rng(41);
  int overlapping = 0, separate = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Box a = random_box(rng);
    const Obb o = random_obb(rng, false);
    // The gap between the boxes along each axis (negative: their projections overlap by that much).
    double gap = -1e300;
    for (int k = 0; k < 3; ++k) {
      const double lo = o.center[k] - o.half_extents[k], hi = o.center[k] + o.half_extents[k];
      gap = std::max(gap, std::max(lo - a.max[k], a.min[k] - hi));
    }
    if (std::abs(gap) < 1e-6) continue;  // within the test's widening of touching
    INFO("trial " << trial << " gap " << gap);
    CHECK(box_obb_overlap(a.min, a.max, o) == (gap < 0.0));
    (gap < 0.0 ? overlapping : separate) += 1;
  }
  CHECK(overlapping > 1000);
  CHECK(separate > 1000);
}

TEST_CASE("the AABB-OBB test is conservative on turned OBBs and separates what a plane parts",
          "[geometry][obb-overlap]") {
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int shared = 0, parted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Box a = random_box(rng);
    const Obb o = random_obb(rng, true);
    // A point of the OBB inside the box: they overlap.
    for (int sample = 0; sample < 64; ++sample) {
      const Eigen::Vector3d s(unit(rng), unit(rng), unit(rng));
      if (box_contains(a, o.center + o.axes * s.cwiseProduct(o.half_extents))) {
        INFO("trial " << trial);
        CHECK(box_obb_overlap(a.min, a.max, o));
        ++shared;
        break;
      }
    }
    // Every corner of the OBB beyond one face of the box: a box axis parts them.
    const auto c = corners(o);
    for (int k = 0; k < 3; ++k) {
      bool above = true, below = true;
      for (const Eigen::Vector3d& p : c) {
        above = above && p[k] > a.max[k] + 1e-6;
        below = below && p[k] < a.min[k] - 1e-6;
      }
      if (above || below) {
        INFO("trial " << trial << " axis " << k);
        CHECK_FALSE(box_obb_overlap(a.min, a.max, o));
        ++parted;
        break;
      }
    }
  }
  CHECK(shared > 1000);
  CHECK(parted > 1000);
}
