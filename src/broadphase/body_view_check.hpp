#pragma once
// The broad phase's check of a body's data at its entry points (the searches and their brute-force references).
// Internal to the broad phase.

#include "broadphase/traversal.hpp"

namespace clothcd::broadphase::detail {

/// Throws std::invalid_argument naming the body when its topology or boxes are missing, or, with `needs_bvh`, when its
/// hierarchy is missing or not built.
void check_view(const BodyView& view, bool needs_bvh);

}  // namespace clothcd::broadphase::detail
