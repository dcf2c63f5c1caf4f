#pragma once
/// @file
/// The broad phase's slow, obviously correct reference: every vertex against every face and every edge against every
/// edge by their swept boxes, or every face against every face (quadratic; for tests). The hierarchy searches of
/// traversal.hpp must find exactly these pairs, with the same rules: pairs sharing a vertex are skipped inside a body
/// (face pairs excepted), and each vertex is taken once, from the triangle that owns it. A gap takes the pairs whose
/// boxes are within it along every axis, by the test that the searches take with a gap bound (gap_bound.hpp).

#include "broadphase/candidates.hpp"
#include "broadphase/traversal.hpp"

namespace clothcd::broadphase {

/// The reference for find_self_candidates: the same pairs, by testing every owned vertex against every face not
/// holding it and every edge against every later edge sharing no vertex with it (SearchedPairs::FaceFace: every face
/// against every later face), by their boxes overlapping, or with `gap` (>= 0) being within it of each other along
/// every axis (TraversalSettings::gap_bound; a gap of 0 is the overlap test). Throws std::invalid_argument when the
/// body's topology or boxes are missing (its hierarchy is not used).
void brute_force_self_candidates(const BodyView& body, CandidateSet& out,
                                 SearchedPairs pairs = SearchedPairs::VertexFaceEdgeEdge, double gap = 0.0);

/// The reference for find_pair_candidates: every owned vertex of each body against every face of the other and every
/// edge of `a` against every edge of `b` (SearchedPairs::FaceFace: every face of `a` against every face of `b`), by
/// their boxes as brute_force_self_candidates tests them. Throws std::invalid_argument when a body's topology or boxes
/// are missing.
void brute_force_pair_candidates(const BodyView& a, const BodyView& b, CandidateSet& out,
                                 SearchedPairs pairs = SearchedPairs::VertexFaceEdgeEdge, double gap = 0.0);

}  // namespace clothcd::broadphase
