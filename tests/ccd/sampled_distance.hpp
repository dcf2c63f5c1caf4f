#pragma once
// The slow distance reference of the thickness tests: the distance of two moving primitives sampled on a grid of their
// parameters at evenly spaced times. A sample is a real pair of points, so the result is an upper bound of the true
// minimum distance: a sampled distance <= h proves that the pair comes within h.
#include <algorithm>
#include <array>
#include <limits>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::test {

/// Upper bound of the distance at time t: minimum over a `grid` x `grid` parameter grid of each primitive.
inline double sampled_distance(const ccd::CcdQuery& query, double t, int grid) {
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = (1 - t) * query.start[i] + t * query.end[i];
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= grid; ++i) {
    for (int j = 0; j <= grid; ++j) {
      const double u = static_cast<double>(i) / grid, v = static_cast<double>(j) / grid;
      if (query.kind == PairKind::VertexFace) {
        if (u + v > 1) continue;
        best = std::min(best, (x[0] - (x[1] + u * (x[2] - x[1]) + v * (x[3] - x[1]))).norm());
      } else {
        best = std::min(best, ((x[0] + u * (x[1] - x[0])) - (x[2] + v * (x[3] - x[2]))).norm());
      }
    }
  }
  return best;
}

/// Upper bound of the minimum distance over the step: sampled_distance at `times` + 1 evenly spaced times.
inline double sampled_min_distance(const ccd::CcdQuery& query, int grid, int times) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= times; ++k)
    best = std::min(best, sampled_distance(query, static_cast<double>(k) / times, grid));
  return best;
}

}  // namespace clothcd::test
