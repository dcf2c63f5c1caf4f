#pragma once
/// @file
/// The broad phase's slow, obviously correct reference: every vertex against every face and every edge against every
/// edge by their swept boxes (quadratic; for tests). The hierarchy searches of traversal.hpp must find exactly these
/// pairs, with the same rules: pairs sharing a vertex are skipped inside a body, and each vertex is taken once, from
/// the triangle that owns it.

#include "broadphase/candidates.hpp"
#include "broadphase/traversal.hpp"

namespace clothcd::broadphase {

/// The reference for find_self_candidates: the same pairs, by testing every owned vertex against every face not
/// holding it and every edge against every later edge sharing no vertex with it. Throws std::invalid_argument when the
/// body's topology or boxes are missing (its hierarchy is not used).
void brute_force_self_candidates(const BodyView& body, CandidateSet& out);

/// The reference for find_pair_candidates: every owned vertex of each body against every face of the other and every
/// edge of `a` against every edge of `b`. Throws std::invalid_argument when a body's topology or boxes are missing.
void brute_force_pair_candidates(const BodyView& a, const BodyView& b, CandidateSet& out);

}  // namespace clothcd::broadphase
