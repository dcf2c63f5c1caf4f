#pragma once
// Private: root brackets for the expansion tier of the thickness-0 CCD (expansion_collision.cpp): the roots in [0, 1]
// of its polynomials as candidate times (grid times, brackets of one simple root, exact rational times), the exact
// sign of another polynomial at a candidate, and a double lower bound of a candidate's time.
#include <optional>
#include <vector>

#include "ccd/expansion_polynomial.hpp"
#include "geometry/expansion.hpp"

namespace clothcd::ccd::detail {

/// A candidate time: the grid time lo (point), or the only root of a polynomial (D unless D is identically zero) in
/// the open (lo, hi), with the exact sign sign_lo at lo and the opposite sign at hi (both on the grid), or a rational
/// time.
struct Candidate {
  bool point = false;             ///< The grid time lo (= hi).
  bool rational = false;          ///< The time num / den (den > 0): a double root of a quadratic sign polynomial, or a
                                  ///< bracketed root found rational.
  Expansion num, den;             ///< The rational time.
  Expansion lo, hi;               ///< The bracket (both the time of a point).
  int sign_lo = 0;                ///< The exact sign of root_of at lo.
  const Poly* root_of = nullptr;  ///< The polynomial whose root is bracketed (D, or a sign polynomial when D == 0).
  double d_lo = 0.0, d_hi = 0.0;  ///< Estimates of root_of at lo and hi.
  bool bisect_next = false;       ///< Whether the next shrinking step bisects the bracket (else a secant guess).
  bool pin_tried = false;         ///< Whether a rational alignment time was tried as the bracketed root.
};

/// The candidate at the grid time t.
[[nodiscard]] Candidate point_at(const Expansion& t);

/// filtered_sign at the bracketed root (m the bracket's middle, distance half its width plus the rounding of m).
[[nodiscard]] int filtered_sign(const Candidate& c, const Poly& p, int n);

/// Exact sign of p at the candidate, or nullopt when it cannot be decided (the bracket may shrink, or turn out a grid
/// time, on the way).
[[nodiscard]] std::optional<int> sign_at(Candidate& c, const Poly& p);

/// Appends the candidates for the roots of d (degree n >= 1) in (lo, hi), in increasing order; d(lo), d(hi) have the
/// exact signs s_lo, s_hi, and depth is the subdivision depth of [lo, hi] (0 for [0, 1]). The candidates point to d.
/// False on giving up.
[[nodiscard]] bool isolate(const Poly& d, int n, const Expansion& lo, int s_lo, const Expansion& hi, int s_hi,
                           int depth, std::vector<Candidate>& out);

/// A double not above the candidate's time and at most kToiBracket = 2^-24 (plus a rounding) below it: within a few
/// units in the last place of a grid or rational time, within kToiBracket of a bracketed root (the bracket is shrunk
/// first, since the predicate may have held on a wide one). nullopt when the bracket does not shrink that far or a
/// rational time has no such double found (the GMP reference then gives the time).
[[nodiscard]] std::optional<double> lower_bound(Candidate& c);

/// Appends the candidates for the roots of p in [0, 1] (none when its degree is below 1); they point to p. A double
/// root of a quadratic (zero discriminant) is the rational -p1 / (2 p2), which bisection could never bracket; other
/// roots are simple, bracketed by the end signs of pieces where p is monotone (linear p, a quadratic on either side of
/// its vertex), else isolated on the grid. False on giving up.
[[nodiscard]] bool add_roots(const Poly& p, std::vector<Candidate>& out);

/// Whether the candidate's time (every time of its bracket) is at or after the time t.
[[nodiscard]] bool not_before(const Candidate& c, double t);

}  // namespace clothcd::ccd::detail
