#pragma once
// Private: the fast tier of the thickness-0 CCD (continuous_collision.cpp), in plain floating point. Every rounded
// value carries an error bound from the magnitudes of the terms it is made of, fixed once per query for W's points
// and D (a semi-static filter): a sign is certain when the rounded value exceeds its bound, so no interval bounds are
// carried through the operations.
#include <array>
#include <optional>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd::detail {

/// A proven time of impact lies at most this far (a fraction of the step) before the earliest contact.
inline constexpr double kToiTolerance = 0x1p-21;

/// D(t) = det(x1 - x0, x2 - x0, x3 - x0) on a piece of the step: its Bernstein coefficients, the middle two times 3
/// (so the ends are tripled; signs and sign changes are those of the coefficients), rounded, each within `error` of
/// the exact coefficients of D on the piece.
struct RoundedCubic {
  std::array<double, 4> b{};  ///< Rounded coefficients.
  double error = 0.0;         ///< Bound on each coefficient's rounding error.
};

/// W's points by axis: points[axis][m], the fourth point of a vertex-face pair a copy of the first (conv W and W's
/// boxes are the same, and every loop over the points runs four lanes).
using WPoints = std::array<std::array<double, 4>, 3>;

/// A thickness-0 query as the difference points W (vertex-face: v - f_j, edge-edge: a_i - b_j; the origin is in
/// conv W(t) at a contact) at the step's ends, and D on the step, with the bounds of their rounding errors.
struct RoundedQuery {
  int count = 0;               ///< 3 points (vertex-face) or 4 (edge-edge).
  WPoints start{};             ///< W(0), each coordinate one rounded difference (its sign exact).
  WPoints end{};               ///< W(1), likewise.
  WPoints point_error{};       ///< Bound on |W(t) - point_at(t)| per coordinate, for every t in [0, 1].
  WPoints magnitude{};         ///< Bound on |W(t)| and |point_at(t)| per coordinate, for every t in [0, 1].
  double halving_error = 0.0;  ///< Bound on the error one de Casteljau halving adds to a RoundedCubic.
  RoundedCubic d;              ///< D on the whole step.
};

/// True when every coordinate is at most 2^100 in magnitude: the floating-point tiers' range (at both thicknesses),
/// where no product of theirs can overflow.
[[nodiscard]] bool fits_floating_point_tiers(const CcdQuery& query);

/// The query as a RoundedQuery; nullopt outside fits_floating_point_tiers (the exact tiers decide).
[[nodiscard]] std::optional<RoundedQuery> rounded_query(const CcdQuery& query);

/// W at time t in [0, 1], rounded: (1 - t) W(0) + t W(1), within point_error of the exact W(t).
void point_at(const RoundedQuery& query, double t, WPoints& w);

/// The Bernstein coefficients on a piece of the 2D cross product W_a x W_b in the projection dropping axis k, from W
/// at the piece's ends (as point_at gives it): each within cross_error(query, a, b, k) of the exact coefficients.
[[nodiscard]] std::array<double, 3> cross_coefficients(const WPoints& piece_start, const WPoints& piece_end, int a,
                                                       int b, int k);

/// Bound on the error of cross_coefficients(..., a, b, k) on any piece of the query's step.
[[nodiscard]] double cross_error(const RoundedQuery& query, int a, int b, int k);

/// The two halves of `cubic`'s piece by de Casteljau halving, each error grown by `added_error`.
void halve(const RoundedCubic& cubic, double added_error, RoundedCubic& left, RoundedCubic& right);

/// What the search of a query's step decides.
enum class SearchOutcome { Clear, Hit, Undecided };

/// The search's answer: with Hit, toi is a lower bound of the earliest contact at most kToiTolerance below it; with
/// Undecided, no contact lies before toi.
struct SearchAnswer {
  SearchOutcome outcome = SearchOutcome::Clear;
  double toi = 1.0;
};

/// Subdivides the step, left half first, deciding each piece by its W boxes, D's Bernstein signs and the projected
/// triangles of W (see continuous_collision.cpp). Pieces that start after `until` are cleared. `deep` lets undecided
/// pieces split below depth 4 within a budget. The caller has settled a possible exact touch at either end.
[[nodiscard]] SearchAnswer search_step(const RoundedQuery& query, bool deep, double until);

/// True when D may vanish at the step's start (end = 0) or end (end = 1) and the origin may be in conv W there: no
/// piece ending there could be decided (an exact touch), so it is settled by an exact test of that end first.
[[nodiscard]] bool possible_touch_at(const RoundedQuery& query, int end);

/// True when a point of W is exactly the origin at the step's start (end = 0) or end (end = 1): a vertex on a face's
/// corner, two edges sharing an end point.
[[nodiscard]] bool has_zero_point(const RoundedQuery& query, int end);

/// True when the origin is certainly outside conv W(t) for every t in [0, 1): some coordinate has one strict sign at
/// t = 0 and that sign or zero at t = 1 for every point of W, so a touch at the end is the only possible contact.
[[nodiscard]] bool outside_before_end(const RoundedQuery& query);

}  // namespace clothcd::ccd::detail
