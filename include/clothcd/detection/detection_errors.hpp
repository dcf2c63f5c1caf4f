#pragma once
/// @file
/// The two ways CollisionDetector::detect() stops before its answer: the collision budget ran out, or the caller
/// cancelled the call. Either way the detector stays usable: the next call searches its step in full.

#include <stdexcept>

namespace clothcd {

/// Thrown by CollisionDetector::detect() when a step has more collisions than DetectorSettings::max_collisions: the
/// search stops as soon as a thread's count passes the budget, so collisions() is at least the budget plus one and at
/// most that plus a few blocks, not the step's total. A simulation that meets it has exploded (a time step too large,
/// a constraint gone wrong): retry the step with a smaller time step, or go back to the last good state.
class CollisionBudgetExceeded : public std::runtime_error {
 public:
  /// The collisions found when the search stopped, and the budget (DetectorSettings::max_collisions).
  CollisionBudgetExceeded(long collisions, long max_collisions);
  /// Collisions found when the search stopped (more than max_collisions()).
  [[nodiscard]] long collisions() const noexcept { return collisions_; }
  /// The budget that was exceeded.
  [[nodiscard]] long max_collisions() const noexcept { return max_collisions_; }

 private:
  long collisions_;
  long max_collisions_;
};

/// Thrown by CollisionDetector::detect() when its cancel check (CollisionDetector::set_cancel_check) returned true.
class DetectionCancelled : public std::runtime_error {
 public:
  /// With the message "collision detection cancelled".
  DetectionCancelled();
};

}  // namespace clothcd
