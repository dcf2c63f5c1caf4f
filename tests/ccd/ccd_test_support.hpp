#pragma once
// Helpers for the CCD tests: building queries and checking every CCD entry point against an expected answer.
#include <catch2/catch.hpp>

#include <array>

#include "ccd/exact_reference.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::test {

using Eigen::Vector3d;

/// A query from its four start and four end points (CcdQuery order).
inline ccd::CcdQuery make_query(PairKind kind, const std::array<Vector3d, 4>& start,
                                const std::array<Vector3d, 4>& end) {
  ccd::CcdQuery query;
  query.kind = kind;
  query.start = start;
  query.end = end;
  return query;
}

/// The exact earliest contact of the query, by the rational reference (narrowed to 2^-40).
inline ccd::exact::ContactTimeBounds exact_contact_time_of(const ccd::CcdQuery& query) {
  ccd::exact::RationalPoints points;
  for (int p = 0; p < 4; ++p) {
    for (int d = 0; d < 3; ++d) {
      points[p][d] = mpq_class(query.start[p][d]);
      points[p + 4][d] = mpq_class(query.end[p][d]);
    }
  }
  return ccd::exact::exact_contact_time(query.kind, points);
}

/// The query with every coordinate multiplied by `scale` (a power of two keeps it exact).
inline ccd::CcdQuery scaled(ccd::CcdQuery query, double scale) {
  for (int i = 0; i < 4; ++i) {
    query.start[i] *= scale;
    query.end[i] *= scale;
  }
  return query;
}

/// Thickness 0, every query decided exactly (ccd::CcdSettings::decide_exactly).
inline ccd::CcdSettings exact_settings() {
  ccd::CcdSettings settings;
  settings.decide_exactly = true;
  return settings;
}

/// Thickness 0, the approximate mode: undecided queries reported as conservative hits.
inline ccd::CcdSettings approximate_settings() {
  ccd::CcdSettings settings;
  settings.decide_exactly = false;
  return settings;
}

/// Checks the answer of the approximate mode against the exact mode's `exact`: never a miss, a proven hit only for a
/// real one, and the same answer where it is not conservative. (That its toi is a lower bound is checked on the exact
/// reference in test_ccd_differential.cpp.)
inline void check_conservative_answer(const ccd::CcdQuery& query, const ccd::CcdResult& exact) {
  const ccd::CcdResult fast = ccd::continuous_collision(query, approximate_settings());
  if (exact.hit) CHECK(fast.hit);
  if (!exact.hit) CHECK(fast.state != ccd::CcdState::Hit);
  if (fast.state != ccd::CcdState::ConservativeHit) {
    CHECK(fast.hit == exact.hit);
    CHECK(fast.toi == exact.toi);
  }
}

/// Checks the exact reference, the fast path in both modes and (for colliding queries) that no filter culls.
inline void check_query(const ccd::CcdQuery& query, bool expected) {
  CHECK(ccd::exact_collision_reference(query) == expected);
  const ccd::CcdResult result = ccd::continuous_collision(query, exact_settings());
  CHECK(result.hit == expected);
  CHECK(result.state == (expected ? ccd::CcdState::Hit : ccd::CcdState::Separated));
  check_conservative_answer(query, result);
  if (expected) {
    CHECK_FALSE(ccd::nonpenetration_filter_culls(query));
    CHECK_FALSE(ccd::projection_filter_culls(query));
    CHECK_FALSE(ccd::projection_filter_culls(query, {}, ccd::ProjectionFilterOptions{true}));
    CHECK_FALSE(ccd::combined_filters_cull(query));
  }
}

}  // namespace clothcd::test
