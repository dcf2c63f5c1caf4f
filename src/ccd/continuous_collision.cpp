// The fast, safe CCD narrow phase (section 2.2's coplanarity cubic, made exact-safe).
//
// Both pair kinds are one question: is the origin in conv W(t) for some t in [0, 1], with W = {v - f_i} (vertex-face)
// or W = {a_i - b_j} (edge-edge), all linear in t (see exact_reference.cpp for why this is equivalent). The fast tier
// (rounded_search.cpp) subdivides the step in floating point, with error bounds fixed per query: it clears pieces
// where the origin is certainly outside W's boxes, D(t) = det(x1 - x0, x2 - x0, x3 - x0) has no root or every
// projected triangle of W excludes the origin, and proves hits where D changes sign while the origin is strictly
// inside a projected triangle (the time of impact bracketed to within 2^-21 of the step).
// Undecided pieces split on to depth 4, and with CcdSettings::decide_exactly deeper within a budget of pieces; a
// query still undecided then goes to the exact expansion tier (expansion_collision.cpp), and what that cannot decide
// to the exact rational reference, so no collision is ever missed and every hit is proven; before them, a query whose
// primitives share a coordinate plane for the whole step (two points of W pinned to it, pinned_segment_contact.hpp)
// is decided on that plane, where it is a segment test that interval arithmetic can prove. A possible exact touch at
// t = 0 or 1, which no piece ending there could decide, is settled before any subdivision by an exact test of that
// end's positions: a touch at the start is the earliest contact, and one at the end the only one when a coordinate
// separates W from the origin for every t < 1 (a collapsing cloth); other such queries go to the exact tiers (so a
// degenerate step costs a few microseconds a pair, not the exact tiers' hundreds). Without decide_exactly
// (the approximate mode) an undecided query is a conservative hit instead (toi: where D may first vanish, 0 for a
// touch at the ends). With thickness h > 0 the projection filter runs first, then the Lipschitz-bounded distance
// search of thickness_contact.cpp decides (no rational arithmetic).
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "ccd/exact_reference.hpp"
#include "ccd/expansion_collision.hpp"
#include "ccd/pinned_segment_contact.hpp"
#include "ccd/rounded_search.hpp"
#include "ccd/thickness_contact.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "geometry/pair_distance.hpp"

namespace clothcd::ccd {

namespace {

exact::RationalPoints rational_points(const CcdQuery& query) {
  exact::RationalPoints points;
  for (int i = 0; i < 4; ++i) {
    for (int d = 0; d < 3; ++d) {
      points[i][d] = mpq_class(query.start[i][d]);
      points[i + 4][d] = mpq_class(query.end[i][d]);
    }
  }
  return points;
}

bool all_finite(const CcdQuery& query) {
  for (int i = 0; i < 4; ++i)
    if (!query.start[i].allFinite() || !query.end[i].allFinite()) return false;
  return true;
}

// Approximate contact parameters and unit normal at time t (from the second primitive towards the first), computed on
// the positions scaled by a power of two to magnitudes about 1 (both are scale-invariant; products of huge coordinates
// overflowed into NaN parameters from about 1e77).
void fill_contact_geometry(const CcdQuery& query, CcdResult& result) {
  double largest = 0.0;
  for (int i = 0; i < 4; ++i)
    largest = std::max({largest, query.start[i].cwiseAbs().maxCoeff(), query.end[i].cwiseAbs().maxCoeff()});
  const double scale = largest > 0.0 ? std::ldexp(1.0, -std::ilogb(largest)) : 1.0;
  std::array<Eigen::Vector3d, 4> x, start;
  for (int i = 0; i < 4; ++i) {
    start[i] = scale * query.start[i];
    x[i] = start[i] + result.toi * (scale * query.end[i] - start[i]);
  }
  const geometry::ContactFrame frame =
      query.kind == PairKind::VertexFace
          ? geometry::point_triangle_contact_frame(x, start[0] - start[1])
          : geometry::segment_segment_contact_frame(x, (start[0] + start[1]) - (start[2] + start[3]));
  result.parameters = frame.parameters;
  result.normal = frame.normal;
}

CcdResult make_hit(const CcdQuery& query, double toi, CcdState state) {
  CcdResult result;
  result.hit = true;
  result.toi = toi;
  result.state = state;
  fill_contact_geometry(query, result);
  return result;
}

// Thickness 0. Queries the fast tier leaves undecided are reported as conservative hits unless decide_exactly; those
// too large for the fast path always go to the exact tiers. A query that certainly has no contact until `until` is
// separated (see continuous_collision_until).
CcdResult contact_without_thickness(const CcdQuery& query, bool decide_exactly, bool nonpenetration_checked,
                                    double until) {
  if (!nonpenetration_checked && nonpenetration_filter_culls(query)) return CcdResult{};
  if (const std::optional<detail::RoundedQuery> rounded = detail::rounded_query(query)) {
    double undecided_from = 0.0;  // lower bound of the earliest contact when undecided
    const bool touch_at_start = detail::possible_touch_at(*rounded, 0);
    const bool touch_at_end = detail::possible_touch_at(*rounded, 1);
    if (touch_at_start || (touch_at_end && detail::outside_before_end(*rounded))) {
      // A touch at the start is the earliest contact; one at the end is the only contact when there is none before.
      const int at = touch_at_start ? 0 : 1;
      const std::optional<bool> touches = detail::has_zero_point(*rounded, at) ? std::optional<bool>(true)
                                                                               : detail::touches_at_step_end(query, at);
      if (at == 1 && until < 1.0) return CcdResult{};  // the touch at the end is the only contact
      if (touches && *touches) return make_hit(query, at, CcdState::Hit);
      if (touches && at == 1) return CcdResult{};
    } else if (!touch_at_end) {
      const detail::SearchAnswer answer = detail::search_step(*rounded, decide_exactly, until);
      if (answer.outcome == detail::SearchOutcome::Clear) return CcdResult{};
      if (answer.outcome == detail::SearchOutcome::Hit) return make_hit(query, answer.toi, CcdState::Hit);
      undecided_from = answer.toi;
      // No contact before undecided_from, so the exact tiers' time of impact (at most kToiTolerance below the contact)
      // would come after `until`.
      if (undecided_from - detail::kToiTolerance > until) return CcdResult{};
    }
    if (const std::optional<detail::PinnedAnswer> pinned = detail::pinned_segment_contact(query))
      return pinned->hit ? make_hit(query, pinned->toi, CcdState::Hit) : CcdResult{};
    if (!decide_exactly) return make_hit(query, undecided_from, CcdState::ConservativeHit);
  }
  if (const std::optional<exact::ExactAnswer> answer = detail::expansion_collision(query))
    return answer->hit ? make_hit(query, answer->toi, CcdState::Hit) : CcdResult{};
  const exact::ContactTimeBounds contact = exact::exact_contact_time(query.kind, rational_points(query));
  CcdResult result = contact.hit ? make_hit(query, contact.lo, CcdState::Hit) : CcdResult{};
  result.exact_fallback = true;
  return result;
}

}  // namespace

void validate_query(const CcdQuery& query, const CcdSettings& settings) {
  if (!all_finite(query)) throw std::invalid_argument("CCD query has a NaN or infinite coordinate");
  if (!std::isfinite(settings.thickness) || settings.thickness < 0.0)
    throw std::invalid_argument("CCD thickness must be finite and >= 0, got " + std::to_string(settings.thickness));
}

CcdResult continuous_collision_until(const CcdQuery& query, const CcdSettings& settings, CcdFilter applied,
                                     double until) {
  if (!all_finite(query) || !(settings.thickness >= 0.0) || !std::isfinite(settings.thickness)) {
    CcdResult result;
    result.hit = true;
    result.toi = 0.0;
    result.state = CcdState::ConservativeHit;
    return result;
  }
  const bool nonpenetration_checked = applied == CcdFilter::NonPenetration || applied == CcdFilter::Combined;
  const bool projection_checked = applied == CcdFilter::Projection || applied == CcdFilter::Combined;
  if (settings.thickness == 0.0)
    return contact_without_thickness(query, settings.decide_exactly, nonpenetration_checked, until);
  if (!projection_checked && projection_filter_culls(query, settings)) return CcdResult{};
  if (detail::fits_floating_point_tiers(query)) return detail::thick_contact(query, settings.thickness);
  // Coordinates this large could overflow the double distances: report a conservative hit. (Proving the touch on the
  // exact path only changed the state label, and its rational root isolation can take minutes on such magnitudes.)
  return make_hit(query, 0.0, CcdState::ConservativeHit);
}

CcdResult continuous_collision_after_filter(const CcdQuery& query, const CcdSettings& settings, CcdFilter applied) {
  return continuous_collision_until(query, settings, applied, 1.0);
}

CcdResult continuous_collision(const CcdQuery& query, const CcdSettings& settings) {
  return continuous_collision_after_filter(query, settings, CcdFilter::None);
}

bool exact_collision_reference(const CcdQuery& query) {
  validate_query(query);
  return exact::exact_collision(query.kind, rational_points(query)).hit;
}

std::size_t continuous_collision_batch(const std::vector<CcdQuery>& queries, const std::vector<std::uint8_t>& keep,
                                       const CcdSettings& settings, std::vector<CcdResult>& results) {
  if (!keep.empty() && keep.size() != queries.size())
    throw std::invalid_argument("continuous_collision_batch: keep has " + std::to_string(keep.size()) +
                                " entries for " + std::to_string(queries.size()) + " queries");
  results.resize(queries.size());
  std::size_t hits = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    results[i] = keep.empty() || keep[i] ? continuous_collision(queries[i], settings) : CcdResult{};
    hits += results[i].hit ? 1 : 0;
  }
  return hits;
}

}  // namespace clothcd::ccd
