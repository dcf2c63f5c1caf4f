#pragma once
// The time windows of the earliest-impact search (internal): consecutive parts [from, to] of the step, searched in
// turn until one holds a contact. A window's candidates are the pairs whose boxes over that part meet. On a fast
// motion their count grows faster than the window's length (boxes grow along the motion), so short windows cost
// less per unit of time; on a slow one most candidates are pairs close all the time (neighbours of a dense mesh),
// which every window pays for again, so long windows cost less. Each window also costs a refit of the boxes,
// whatever its length. The schedule starts with a window in which the mesh moves about half an edge length, then sizes
// each next window from the counts measured in the last two.

#include "broadphase/body_topology.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// How far a body moves over the step in units of its own size: the mean displacement of its vertices from `start`
/// to `end` divided by the mean length of its edges at `start` (0 without motion, infinity when every edge has length
/// 0 and something moves).
[[nodiscard]] double relative_motion(const broadphase::BodyTopology& topology, const Vertices& start,
                                     const Vertices& end);

/// Consecutive windows [from, to] covering the step, sized from the motion and the cost of the ones before.
class WindowSchedule {
 public:
  /// `motion`: the vertices' mean displacement over the step divided by the mean edge length (>= 0); `fixed_cost`:
  /// what a window costs besides its candidates, in candidates (> 0). The first window is [0, L]: L the largest
  /// power of two at most 1/16 and at most 1 / (2 motion), and at least 2^-10.
  WindowSchedule(double motion, double fixed_cost);

  /// Start of the current window (a dyadic fraction of the step).
  [[nodiscard]] double from() const { return from_; }
  /// End of the current window (a dyadic fraction of the step, 1 for the last window).
  [[nodiscard]] double to() const { return to_; }
  /// True when the current window ends the step.
  [[nodiscard]] bool last() const { return to_ == 1.0; }

  /// Moves to the next window after the current one had `candidates` candidates. The second window is twice as long
  /// as the first. Later ones fit candidates = s length^p to the last two windows of different lengths: with p <= 1/2
  /// the next window is 8 times as long, with p <= 1 twice, else the power of two nearest the length that costs least
  /// per unit of time, (fixed_cost / (s (p - 1)))^(1/p), from 1/8 to 2 times the current length, and at least 2^-10.
  /// The window takes the rest of the step when that is shorter than twice its length.
  void advance(double candidates);

 private:
  double fixed_cost_;
  double from_ = 0.0, to_;
  double last_length_ = 0.0, last_candidates_ = 0.0;  // the window before the current one (length 0: none yet)
  double exponent_ = 0.0, coefficient_ = 0.0;         // p and s last fitted (exponent 0: no fit yet)
};

}  // namespace clothcd::detail
