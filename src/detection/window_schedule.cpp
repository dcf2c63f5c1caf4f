// The earliest-impact search's time windows (see window_schedule.hpp).
#include "window_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace clothcd::detail {

namespace {

constexpr int kShortestExponent = -10;  // windows at least 2^-10 of the step long
constexpr int kLongestFirstExponent = -4;
constexpr int kMostDoublings = 3;  // a window 1/8 to 8 times as long as the last

// The exponent of the power of two nearest `length` on a logarithmic scale, within [-64, 64] (-64 for 0 or NaN).
int nearest_exponent(double length) {
  if (!(length > 0.0)) return -64;
  return static_cast<int>(std::lround(std::clamp(std::log2(length), -64.0, 64.0)));
}

}  // namespace

double relative_motion(const broadphase::BodyTopology& topology, const Vertices& start, const Vertices& end) {
  double displacement = 0.0, edge_length = 0.0;
  for (Eigen::Index v = 0; v < start.rows(); ++v) displacement += (end.row(v) - start.row(v)).norm();
  for (int e = 0; e < topology.edge_count(); ++e) {
    edge_length += (start.row(topology.edges[2 * static_cast<std::size_t>(e)]) -
                    start.row(topology.edges[2 * static_cast<std::size_t>(e) + 1]))
                       .norm();
  }
  if (displacement == 0.0) return 0.0;
  const double vertices = static_cast<double>(std::max<Eigen::Index>(1, start.rows()));
  const double edges = static_cast<double>(std::max(1, topology.edge_count()));
  return (displacement / vertices) / (edge_length / edges);
}

WindowSchedule::WindowSchedule(double motion, double fixed_cost) : fixed_cost_(fixed_cost) {
  int exponent = kLongestFirstExponent;
  if (motion > 0.5) exponent = -static_cast<int>(std::ceil(std::log2(std::min(2.0 * motion, 0x1p20))));
  to_ = std::ldexp(1.0, std::clamp(exponent, kShortestExponent, kLongestFirstExponent));
}

void WindowSchedule::advance(double candidates) {
  const double length = to_ - from_;
  const int current = nearest_exponent(length);
  int next = current + 1;  // the second window: twice the first, for a first measurement of the growth
  if (last_length_ > 0.0 && last_length_ != length && last_candidates_ > 0.0 && candidates > 0.0) {
    exponent_ = std::log(candidates / last_candidates_) / std::log(length / last_length_);
    coefficient_ = candidates / std::pow(length, exponent_);
  }
  if (last_length_ > 0.0) {
    // Per unit of time a window of length L costs (fixed_cost + s L^p) / L: less for longer windows when p <= 1 (grown
    // by 8 when p <= 1/2, else doubled), least at the length below when p > 1 (but at most doubled: the fit is local).
    if (exponent_ <= 0.5) {
      next = current + kMostDoublings;
    } else if (exponent_ <= 1.0) {
      next = current + 1;
    } else {
      const double best = std::pow(fixed_cost_ / (coefficient_ * (exponent_ - 1.0)), 1.0 / exponent_);
      next = std::clamp(nearest_exponent(best), current - kMostDoublings, current + 1);
    }
    next = std::max(next, kShortestExponent);
  }
  last_length_ = length;
  last_candidates_ = candidates;
  from_ = to_;
  const double next_length = std::ldexp(1.0, next);
  // A rest shorter than this window joins it: a short last window would cost as much as a long one.
  to_ = 1.0 - from_ < 2.0 * next_length ? 1.0 : from_ + next_length;
}

}  // namespace clothcd::detail
