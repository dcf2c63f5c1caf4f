// Swept boxes: each box is grown by half the thickness, so two primitives closer than the thickness at some instant
// have overlapping boxes, and boxes of primitives farther apart than it along an axis do not.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "broadphase/body_topology.hpp"
#include "broadphase/swept_boxes.hpp"

namespace {

using clothcd::Vertices;
using clothcd::broadphase::build_body_topology;
using clothcd::broadphase::compute_swept_boxes;
using clothcd::broadphase::SweptBoxes;

// Boxes of two isolated vertices (one degenerate face each, so both get a vertex box).
SweptBoxes two_point_boxes(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                           const Eigen::Vector3d& b1, double thickness) {
  clothcd::Faces faces(2, 3);
  faces << 0, 0, 0, 1, 1, 1;
  const auto topology = build_body_topology(faces, 2);
  Vertices start(2, 3), end(2, 3);
  start.row(0) = a0.transpose();
  start.row(1) = b0.transpose();
  end.row(0) = a1.transpose();
  end.row(1) = b1.transpose();
  SweptBoxes boxes;
  compute_swept_boxes(topology, start, end, thickness, boxes);
  return boxes;
}

}  // namespace

TEST_CASE("points closer than the thickness at some instant have overlapping boxes", "[broadphase][boxes]") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::pow(10.0, std::floor(8 * fraction(rng)) - 3);  // coordinates from 1e-3 to 1e4
    const double thickness = scale * std::pow(10.0, -1 - 6 * fraction(rng));
    const Eigen::Vector3d a0 = scale * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d a1 = a0 + scale * 0.1 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    // b passes within (just under) the thickness of a at a random instant t.
    const double t = fraction(rng);
    const Eigen::Vector3d direction = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
    const Eigen::Vector3d meeting = a0 + t * (a1 - a0) + direction * thickness * (1.0 - 1e-9 * fraction(rng));
    const Eigen::Vector3d motion = scale * 0.1 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d b0 = meeting - t * motion;
    const Eigen::Vector3d b1 = meeting + (1.0 - t) * motion;
    const SweptBoxes boxes = two_point_boxes(a0, a1, b0, b1, thickness);
    INFO("trial " << trial);
    REQUIRE(boxes.vertices[0].overlaps(boxes.vertices[1]));
  }
}

TEST_CASE("boxes grow by half the thickness, not by all of it", "[broadphase][boxes]") {
  const double thickness = 0.01;
  const Eigen::Vector3d a(0.5, 0.25, -1.0);
  const Eigen::Vector3d apart = a + Eigen::Vector3d(0.0, 1.01 * thickness, 0.0);
  const Eigen::Vector3d close = a + Eigen::Vector3d(0.0, 0.99 * thickness, 0.0);
  const SweptBoxes far = two_point_boxes(a, a, apart, apart, thickness);
  CHECK_FALSE(far.vertices[0].overlaps(far.vertices[1]));
  const SweptBoxes near = two_point_boxes(a, a, close, close, thickness);
  CHECK(near.vertices[0].overlaps(near.vertices[1]));
  // Without thickness the boxes are exactly the swept coordinates.
  const SweptBoxes exact = two_point_boxes(a, apart, apart, a, 0.0);
  CHECK(exact.vertices[0].min[1] == a[1]);
  CHECK(exact.vertices[0].max[1] == apart[1]);
}

TEST_CASE("updating the boxes of moved vertices gives the boxes computed afresh", "[broadphase][boxes]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const int n = 200;
  Vertices start(n, 3), end(n, 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      start(i, c) = coordinate(random);
      end(i, c) = start(i, c) + 0.1 * coordinate(random);
    }
  }
  SweptBoxes updated;
  clothcd::broadphase::compute_swept_vertex_boxes(start, end, 0.01, updated);
  std::vector<std::uint8_t> moved(n, 0);
  for (int i = 0; i < n; i += 7) {
    moved[i] = 1;
    end(i, i % 3) += 0.05;
  }
  clothcd::broadphase::update_swept_vertex_boxes(start, end, 0.01, moved, updated);
  SweptBoxes fresh;
  clothcd::broadphase::compute_swept_vertex_boxes(start, end, 0.01, fresh);
  for (int i = 0; i < n; ++i) {
    INFO("vertex " << i);
    for (int c = 0; c < 3; ++c) {
      CHECK(updated.vertices[i].min[c] == fresh.vertices[i].min[c]);
      CHECK(updated.vertices[i].max[c] == fresh.vertices[i].max[c]);
    }
  }
}
