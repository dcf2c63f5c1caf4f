#pragma once
/// @file
/// The other question a simulator asks of a step: how far along it can everything move without any contact (the
/// collision-free step size of a line search).

#include "clothcd/detection/collision.hpp"

namespace clothcd {

/// What CollisionDetector::earliest_impact finds.
struct EarliestImpact {
  /// The step's earliest time of impact, as a fraction of the step in [0, 1]: never later than the exact earliest
  /// contact of any pair (with DetectorSettings::thickness h > 0: the earliest time some pair comes within h), and at
  /// thickness 0 in the default settings at most 2^-21 (< 1e-6) of the step before it. 1 when nothing comes into
  /// contact during the step (then `hit` is false). No safety factor is applied: a line search that wants a gap takes
  /// a fraction of it (e.g. 0.8 toi), see the README.
  double toi = 1.0;
  /// True when some pair comes into contact (or within the thickness) during the step, at `toi`.
  bool hit = false;
  /// With `hit`: the pair that sets `toi`, as detect() would report it. Among pairs with the same toi, the one
  /// detect() lists first (vertex-face pairs before edge-edge pairs).
  Collision pair;
  /// How many time windows were searched: consecutive parts of the step in time order, stopping at the first that
  /// holds a contact (a window's candidates are the pairs whose boxes over that part meet). The first is the part in
  /// which the mesh moves about half an edge length (at most 1/16 of the step); the next ones are sized from the
  /// candidate counts of the windows before.
  int windows = 0;
};

}  // namespace clothcd
