#pragma once
// The narrow phase for a pair that a culling filter has already examined: the filter checks continuous_collision
// would repeat are skipped, so a batch that filters first does not run the same test twice per surviving pair.

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd::detail {

/// Same result as continuous_collision(query, settings), for a query that `applied` (run with the same settings) did
/// not cull: the non-penetration and projection tests `applied` covers are not run again (both are pure functions of
/// the query, so skipping them cannot change the answer). CcdFilter::None runs everything.
[[nodiscard]] CcdResult continuous_collision_after_filter(const CcdQuery& query, const CcdSettings& settings,
                                                          CcdFilter applied);

}  // namespace clothcd::ccd::detail
