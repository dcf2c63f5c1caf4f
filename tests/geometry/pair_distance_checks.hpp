#pragma once
// Checks of the pair distances (geometry/pair_distance.hpp) against the exact reference
// (geometry/exact_pair_distance.hpp): membership, distance, type, parameters and direction of one pair at one asked
// distance.

#include <catch2/catch.hpp>

#include <gmpxx.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>

#include "geometry/exact_pair_distance.hpp"
#include "geometry/pair_distance.hpp"

namespace clothcd::test {

using Points = std::array<Eigen::Vector3d, 4>;

/// The reference of a pair (vertex-face when `vertex_face`, else edge-edge).
inline geometry::ExactPairDistance reference(bool vertex_face, const Points& x) {
  return vertex_face ? geometry::exact_point_triangle_distance(x[0], x[1], x[2], x[3])
                     : geometry::exact_segment_segment_distance(x[0], x[1], x[2], x[3]);
}

/// True when distance is within kDistanceRelativeError of sqrt(squared), or below the normal range within 2^-1074 of
/// it; checked exactly on squares.
inline bool distance_accurate(double distance, const mpq_class& squared) {
  if (sgn(squared) == 0) return distance == 0.0;
  const mpq_class r(distance), lo(1.0 - kDistanceRelativeError), hi(1.0 + kDistanceRelativeError);
  if (r * r >= lo * lo * squared && r * r <= hi * hi * squared) return true;
  const mpq_class smallest(0x1p-1074), normal(0x1p-1022);
  return squared < normal * normal && (r - smallest) * (r - smallest) <= squared &&
         squared <= (r + smallest) * (r + smallest);
}

/// The record's closest points (from its parameters) lie `distance` apart along `direction`, up to a tolerance
/// relative to the pair's extent.
inline void check_geometry(bool vertex_face, const Points& x, const geometry::PairDistance& record) {
  double extent = 0.0;
  for (const Eigen::Vector3d& y : x) extent = std::max(extent, (y - x[0]).cwiseAbs().maxCoeff());
  const double tolerance = 1e-7 * extent + 1e-300;
  const auto [w1, w2] = record.parameters;
  Eigen::Vector3d first, second;
  if (vertex_face) {
    CHECK(w1 >= -1e-12);
    CHECK(w2 >= -1e-12);
    CHECK(w1 + w2 <= 1.0 + 1e-12);
    first = x[0];
    second = x[1] + w1 * (x[2] - x[1]) + w2 * (x[3] - x[1]);
  } else {
    CHECK(w1 >= 0.0);
    CHECK(w1 <= 1.0);
    CHECK(w2 >= 0.0);
    CHECK(w2 <= 1.0);
    first = x[0] + w1 * (x[1] - x[0]);
    second = x[2] + w2 * (x[3] - x[2]);
  }
  if (record.distance == 0.0) {
    CHECK(record.direction == Eigen::Vector3d::Zero());
  } else {
    CHECK(std::abs(record.direction.norm() - 1.0) < 1e-12);
  }
  CHECK((first - second - record.distance * record.direction).norm() <= tolerance);
}

/// Checks within() at distance d and distance() of one pair against the reference; returns whether it is within.
inline bool check_pair(bool vertex_face, const Points& x, double d) {
  const geometry::ExactPairDistance exact = reference(vertex_face, x);
  const mpq_class dq(d);
  const bool expected = exact.squared_distance < dq * dq;
  geometry::PairDistance within_record;
  within_record.distance = -1.0;
  const bool within = vertex_face ? geometry::point_triangle_within(x[0], x[1], x[2], x[3], d, within_record)
                                  : geometry::segment_segment_within(x[0], x[1], x[2], x[3], d, within_record);
  INFO("points " << x[0].transpose() << " | " << x[1].transpose() << " | " << x[2].transpose() << " | "
                 << x[3].transpose() << " d " << d << " exact squared " << exact.squared_distance.get_d());
  CHECK(within == expected);
  if (within) {
    CHECK(within_record.type == exact.type);
    CHECK(distance_accurate(within_record.distance, exact.squared_distance));
    check_geometry(vertex_face, x, within_record);
  } else {
    CHECK(within_record.distance == -1.0);  // left as it was
  }
  const geometry::PairDistance record = vertex_face ? geometry::point_triangle_distance(x[0], x[1], x[2], x[3])
                                                    : geometry::segment_segment_distance(x[0], x[1], x[2], x[3]);
  CHECK(record.type == exact.type);
  CHECK(distance_accurate(record.distance, exact.squared_distance));
  check_geometry(vertex_face, x, record);
  return expected;
}

}  // namespace clothcd::test
