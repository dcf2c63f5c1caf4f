// The exceptions of an interrupted detect() call (see detection_errors.hpp).
#include "clothcd/detection/detection_errors.hpp"

#include <string>

namespace clothcd {

CollisionBudgetExceeded::CollisionBudgetExceeded(long collisions, long max_collisions)
    : std::runtime_error("collision detection stopped: " + std::to_string(collisions) +
                         " collisions found, more than DetectorSettings::max_collisions = " +
                         std::to_string(max_collisions) + " (a degenerate step: retry it with a smaller time step)"),
      collisions_(collisions),
      max_collisions_(max_collisions) {}

DetectionCancelled::DetectionCancelled() : std::runtime_error("collision detection cancelled") {}

}  // namespace clothcd
