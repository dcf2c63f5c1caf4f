#pragma once
// Private: the thickness-0 CCD of a pair whose primitives share a coordinate plane for the whole step, decided in
// interval arithmetic where the general fast path can only find an exact touch.
#include <optional>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd::detail {

/// A proven answer of the thickness-0 question: hit, and the time of impact within 2^-21 below the earliest contact.
struct PinnedAnswer {
  bool hit = false;  ///< The primitives touch or cross during the step.
  double toi = 1.0;  ///< With hit: a lower bound of the earliest contact time, at most 2^-21 below it.
};

/// The answer when, on some axis, two of the difference points W (vertex-face: v - f_j; edge-edge: a_i - b_j) have
/// exactly the same coordinate at both ends of the step (so for the whole step) while every other one keeps one
/// strict sign there: a vertex sliding through a face's edge in a plane it shares with it, an edge's end through an
/// edge. The origin can then only be in conv W on the segment between those two points, which interval arithmetic
/// decides unless the contact is an exact touch of its end. nullopt when the query has no such axis or the intervals
/// leave it undecided (the exact tiers then decide).
[[nodiscard]] std::optional<PinnedAnswer> pinned_segment_contact(const CcdQuery& query);

}  // namespace clothcd::ccd::detail
