#pragma once
// Private: the middle tier of the thickness-0 CCD, between the floating-point fast tier and the GMP rational reference.
#include <optional>

#include "ccd/exact_reference.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd::detail {

/// The exact answer of the thickness-0 CCD question (same as exact::exact_collision on the query's doubles), computed
/// with floating-point expansions; nullopt when this tier cannot decide it (the coplanarity cubic D with a multiple
/// root, a sign at a root of D that needs a pseudo-quotient or remainder above degree 1, or coordinates spanning more
/// than 180 binary orders of magnitude): the caller then asks the GMP reference.
[[nodiscard]] std::optional<exact::ExactAnswer> expansion_collision(const CcdQuery& query);

/// Whether the query's primitives touch exactly at the step's start (end = 0) or end (end = 1), from those positions
/// with floating-point expansions; nullopt when this tier cannot decide it (the caller then runs the full exact
/// tiers).
[[nodiscard]] std::optional<bool> touches_at_step_end(const CcdQuery& query, int end);

}  // namespace clothcd::ccd::detail
