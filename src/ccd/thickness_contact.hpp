#pragma once
// The thickness (> 0) narrow phase of the CCD: a Lipschitz-bounded search of the distance over the step.
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd::detail {

/// Decides whether the distance of the query's primitives gets <= thickness during t in [0, 1] (thickness > 0, finite
/// coordinates below 2^100 in magnitude). Hit: a sample was certainly within thickness (toi a lower bound of the first
/// contact); ConservativeHit: undecided at the subdivision limit (toi = start of the undecided piece); Separated
/// otherwise. parameters and normal are those of the closest points at toi.
[[nodiscard]] CcdResult thick_contact(const CcdQuery& query, double thickness);

}  // namespace clothcd::ccd::detail
