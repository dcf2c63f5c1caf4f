// Root brackets of the expansion tier of the thickness-0 CCD: the roots in [0, 1] of D (or of a sign polynomial when D
// is identically zero) as candidate times on the time grid, and the exact sign of another polynomial at one.
//   - Roots of D in [0, 1]: Bernstein subdivision on grid times with exact signs; a piece whose Bernstein
//     coefficients have no sign variation has no root, one variation with non-zero ends brackets exactly one
//     (simple) root; a grid time where D is exactly zero is itself a candidate.
//   - The sign of a polynomial P at a bracketed root t*: P's Bernstein coefficients on the bracket of one strict sign
//     give it; otherwise the bracket shrinks (secant guess, then the exact signs of D on both sides of the guess).
//     When P may vanish at t* (touching exactly, or missing by far less than rounding), the pseudo-division
//     lc(P)^k D = Q P + R gives Q(t*) P(t*) = -R(t*); with Q and R at most linear, their signs at t* come from their
//     rational roots placed against the bracket and t* (exact homogeneous evaluation, after scaling by powers of two).
//   - Roots of linear and quadratic sign polynomials (D identically zero) are bracketed on pieces where they are
//     monotone (split at the vertex), a double root as the exact rational -p1 / (2 p2).
#include "ccd/expansion_roots.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace clothcd::ccd::detail {

namespace {

constexpr int kTimeBits = 150;           // every time used is a multiple of 2^-150
constexpr int kMaxIsolationDepth = 120;  // Bernstein subdivision of [0, 1] for the roots (close roots need deep pieces)
constexpr int kMaxRefinements = 40;      // bracket shrinking steps per sign
// Exact sign by pseudo-division when the bracket is narrow at the first step, or after this many narrow brackets that
// exact Bernstein signs left undecided: a sign still undecided after two is most likely exactly zero, which only the
// pseudo-division decides (measured on the handcrafted queries: 2 beats 1, 3, 4, 6 and never).
constexpr int kSharedRootAttempt = 0;
constexpr int kNarrowBracketsBeforeSharedRoot = 2;
constexpr double kNarrowBracket = 1e-12;  // brackets are shrunk to this width before exact Bernstein signs
constexpr double kToiBracket = 0x1p-24;   // a hit's bracket is shrunk to this width for its time of impact
constexpr int kMaxToiRefinements = 64;

// The sign changes of the Bernstein signs (zeros skipped): at least the number of roots in the open piece, and of the
// same parity.
int sign_variations(const BernsteinSigns& signs) {
  int variations = 0, previous = 0;
  for (int i = 0; i < signs.count; ++i) {
    const int s = signs.sign[static_cast<std::size_t>(i)];
    if (s == 0) continue;
    if (previous != 0 && s != previous) ++variations;
    previous = s;
  }
  return variations;
}

// base + offset rounded to the time grid.
Expansion grid_point(const Expansion& base, double offset) {
  // Scaling by the constant powers of two is exact here (like ldexp): offset 2^150 at worst overflows to infinity as
  // ldexp would, and the rounded integer times 2^-150 is 0 or a normal double.
  static_assert(kTimeBits == 150, "the scale factors below are 2^kTimeBits and 2^-kTimeBits");
  return base + Expansion(std::nearbyint(offset * 0x1p150) * 0x1p-150);
}

bool strictly_between(const Expansion& lo, const Expansion& t, const Expansion& hi) {
  return (t - lo).sign() > 0 && (hi - t).sign() > 0;
}

// Shrinks the bracket (or finds the root on the grid). False when it cannot.
bool refine(Candidate& c, const Poly& d) {
  const Expansion width = c.hi - c.lo;
  const double w = width.estimate();
  double f = c.d_lo / (c.d_lo - c.d_hi);  // secant guess of the root's position in the bracket
  if (c.bisect_next || !(f > 0.0 && f < 1.0)) f = 0.5;
  const double spread = c.bisect_next ? 0.0 : 0x1p-16;
  const Expansion a = grid_point(c.lo, w * std::max(f - spread, 0.25 * f));
  const Expansion b = spread == 0.0 ? a : grid_point(c.lo, w * std::min(f + spread, f + 0.75 * (1.0 - f)));
  if (!strictly_between(c.lo, a, c.hi) || !strictly_between(c.lo, b, c.hi) || (b - a).sign() < 0) {
    if (c.bisect_next) return false;
    c.bisect_next = true;
    return refine(c, d);
  }
  double da = 0.0, db = 0.0;
  const int sa = sign_at_time(d, a, da);
  if (sa == 0) {
    c = point_at(a);
    return true;
  }
  const int sb = spread == 0.0 ? sa : sign_at_time(d, b, db);
  if (spread == 0.0) db = da;
  if (sb == 0) {
    c = point_at(b);
    return true;
  }
  if (sa != c.sign_lo) {
    c.hi = a;
    c.d_hi = da;
  } else if (sb != c.sign_lo) {
    c.lo = a;
    c.d_lo = da;
    c.hi = b;
    c.d_hi = db;
  } else {
    c.lo = b;
    c.d_lo = db;
  }
  c.bisect_next = !c.bisect_next && (c.hi - c.lo).estimate() > 0.5 * w;
  return true;
}

// Exact sign of l (degree at most 1) at the root t* of d bracketed by the candidate: l's root rho = num / den is
// placed against the bracket, and inside it against t* by the exact sign of d at rho.
std::optional<int> linear_sign_at_root(const Candidate& c, const Poly& l, const Poly& d) {
  const int n = degree(l);
  if (n <= 0) return n < 0 ? 0 : l[0].sign();
  const Expansion num = -l[0], den = l[1];
  const int slope = l[1].sign();
  const std::optional<int> above_lo = sign_at_rational(Poly{-c.lo, Expansion(1.0)}, num, den);
  if (!above_lo) return std::nullopt;
  if (*above_lo <= 0) return slope;  // rho <= lo < t*
  const std::optional<int> below_hi = sign_at_rational(Poly{-c.hi, Expansion(1.0)}, num, den);
  if (!below_hi) return std::nullopt;
  if (*below_hi >= 0) return -slope;  // t* < hi <= rho
  const std::optional<int> d_at_rho = sign_at_rational(d, num, den);
  if (!d_at_rho) return std::nullopt;
  if (*d_at_rho == 0) return 0;                    // rho = t*, d's only root in the bracket
  return *d_at_rho == c.sign_lo ? slope : -slope;  // rho on lo's side of t*, or on hi's
}

// The sign of p at the bracketed root t* of d when p may vanish there (the bracket could not separate them). With
// lc(p)^k d = q p + r, q(t*) p(t*) = -r(t*); q and r are at most linear when p has degree 2 or deg d - 1, and their
// signs at t* are exact (linear_sign_at_root).
std::optional<int> sign_at_shared_root(const Candidate& c, const Poly& p, const Poly& d) {
  const int np = degree(p), nd = degree(d);
  if (nd == 1) return sign_at_rational(p, -d[0], d[1]);
  if (np == 1) return linear_sign_at_root(c, p, d);
  const std::optional<PseudoDivision> division = pseudo_divide(d, p);
  if (!division) return std::nullopt;
  const Poly& r = division->remainder;
  if (degree(r) < 0) {
    // p divides lc(p)^k d: p's roots in the bracket are roots of d, so t* is p's only possible root there.
    const int at_lo = evaluate(p, c.lo).sign(), at_hi = evaluate(p, c.hi).sign();
    return at_lo * at_hi < 0 ? 0 : at_lo;
  }
  if (degree(division->quotient) > 1 || degree(r) > 1) return std::nullopt;
  const std::optional<int> q_sign = linear_sign_at_root(c, division->quotient, d);
  const std::optional<int> r_sign = linear_sign_at_root(c, r, d);
  if (!q_sign || !r_sign || *q_sign == 0) return std::nullopt;
  return -*r_sign * *q_sign;
}

// The largest double not above t (t in [0, 1]).
double lower_bound(const Expansion& t) {
  double value = t.estimate();
  if ((t - Expansion(value)).sign() < 0) value = std::nextafter(value, 0.0);
  return std::max(value, 0.0);
}

}  // namespace

Candidate point_at(const Expansion& t) {
  Candidate c;
  c.point = true;
  c.lo = c.hi = t;
  return c;
}

int filtered_sign(const Candidate& c, const Poly& p, int n) {
  const double lo = c.lo.estimate(), hi = c.hi.estimate();
  const double distance = 0.5 * (hi - lo) * (1.0 + 1e-10) + 1e-15 * (std::fabs(lo) + std::fabs(hi)) + 0x1p-1000;
  double value;
  return filtered_sign(p, n, 0.5 * (lo + hi), distance, value);
}

std::optional<int> sign_at(Candidate& c, const Poly& p) {
  const int n = degree(p);
  if (n <= 0) return n < 0 ? 0 : p[0].sign();
  if (c.rational) return sign_at_rational(p, c.num, c.den);
  double estimate = 0.0;
  if (c.point) return sign_at_time(p, c.lo, estimate);
  const Poly& d = *c.root_of;
  int narrow_brackets = 0;
  for (int step = 0; step <= kMaxRefinements; ++step) {
    if (c.point) return sign_at_time(p, c.lo, estimate);
    if (const int s = filtered_sign(c, p, n); s != 0) return s;
    if ((c.hi - c.lo).estimate() > kNarrowBracket && refine(c, d)) continue;  // cheaper than exact signs on it
    ++narrow_brackets;
    const BernsteinSigns signs = bernstein_signs(p, n, c.lo, c.hi - c.lo);
    bool positive = true, negative = true;
    for (int i = 0; i < signs.count; ++i) {
      const int s = signs.sign[static_cast<std::size_t>(i)];
      positive = positive && s > 0;
      negative = negative && s < 0;
    }
    if (positive) return 1;
    if (negative) return -1;
    if (degree(d) == 1 || step == kSharedRootAttempt || narrow_brackets == kNarrowBracketsBeforeSharedRoot) {
      const std::optional<int> shared = sign_at_shared_root(c, p, d);
      if (shared || degree(d) == 1) return shared;
    }
    if (!refine(c, d)) break;
  }
  if (c.point) return sign_at_time(p, c.lo, estimate);
  return sign_at_shared_root(c, p, d);
}

bool isolate(const Poly& d, int n, const Expansion& lo, int s_lo, const Expansion& hi, int s_hi, int depth,
             std::vector<Candidate>& out) {
  const Expansion width = hi - lo;
  const int variations = sign_variations(bernstein_signs(d, n, lo, width));
  if (variations == 0) return true;
  if (variations == 1 && s_lo != 0 && s_hi != 0) {
    Candidate c;
    c.lo = lo;
    c.hi = hi;
    c.sign_lo = s_lo;
    c.root_of = &d;
    sign_at_time(d, lo, c.d_lo);  // estimates of the right sign (filtered, else exact)
    sign_at_time(d, hi, c.d_hi);
    out.push_back(c);
    return true;
  }
  if (depth >= kMaxIsolationDepth) return false;
  const Expansion mid = grid_point(lo, 0.5 * width.estimate());
  if (!strictly_between(lo, mid, hi)) return false;
  double estimate = 0.0;
  const int s_mid = sign_at_time(d, mid, estimate);
  if (!isolate(d, n, lo, s_lo, mid, s_mid, depth + 1, out)) return false;
  if (s_mid == 0) out.push_back(point_at(mid));
  return isolate(d, n, mid, s_mid, hi, s_hi, depth + 1, out);
}

std::optional<double> lower_bound(Candidate& c) {
  for (int i = 0; i < kMaxToiRefinements && !c.point && !c.rational && (c.hi - c.lo).estimate() > kToiBracket; ++i)
    if (!refine(c, *c.root_of)) break;
  if (!c.rational) {
    if (!c.point && !((c.hi - c.lo).estimate() <= kToiBracket)) return std::nullopt;
    return lower_bound(c.lo);
  }
  double value = c.num.estimate() / c.den.estimate();
  // value >= 2^-200 keeps the exact product den * value far above the underflow threshold.
  for (int attempt = 0; attempt < 8 && value >= 0x1p-200; ++attempt, value = std::nextafter(value, 0.0))
    if ((c.num - c.den.scaled(value)).sign() >= 0) return std::min(value, 1.0);
  if (c.num.sign() == 0) return 0.0;
  return std::nullopt;
}

bool add_roots(const Poly& p, std::vector<Candidate>& out) {
  const int n = degree(p);
  if (n < 1) return true;
  const Expansion zero(0.0), one(1.0);
  if (n == 2) {
    const int discriminant = (p[1] * p[1] - (p[0] * p[2]).scaled(4.0)).sign();
    if (discriminant < 0) return true;
    if (discriminant == 0) {
      Candidate c;
      c.rational = true;
      const bool negate = p[2].sign() < 0;
      c.num = negate ? p[1] : -p[1];
      c.den = negate ? -p[2].scaled(2.0) : p[2].scaled(2.0);
      if (c.num.sign() >= 0 && (c.den - c.num).sign() >= 0) out.push_back(c);
      return true;
    }
  }
  // Where p is monotone on a piece, its end signs give its roots there directly; bisection would instead follow a
  // root just outside [0, 1] (or two roots 1e-16 apart) down to the grid.
  double at_0 = 0.0, at_1 = 0.0;
  const int s_0 = sign_at_time(p, zero, at_0), s_1 = sign_at_time(p, one, at_1);
  const auto monotone_piece = [&](const Expansion& lo, int s_lo, double d_lo, const Expansion& hi, int s_hi,
                                  double d_hi) {
    if (s_lo == 0) out.push_back(point_at(lo));
    if (s_lo * s_hi < 0) {
      Candidate c;
      c.lo = lo;
      c.hi = hi;
      c.sign_lo = s_lo;
      c.root_of = &p;
      c.d_lo = d_lo;
      c.d_hi = d_hi;
      out.push_back(c);
    }
  };
  const auto finish = [&] {
    if (s_1 == 0) out.push_back(point_at(one));
    return true;
  };
  if (n == 1) {
    monotone_piece(zero, s_0, at_0, one, s_1, at_1);
    return finish();
  }
  if (n == 2) {
    // p' = p1 + 2 p2 t: of one sign on (0, 1) when p'(0) and p'(1) do not have strictly opposite signs.
    if (p[1].sign() * (p[1] + p[2].scaled(2.0)).sign() >= 0) {
      monotone_piece(zero, s_0, at_0, one, s_1, at_1);
      return finish();
    }
    // The vertex -p1 / (2 p2) is inside (0, 1): a grid time g near it where p has the sign opposite to p2 lies
    // between the two roots, so p is monotone on [0, g] and on [g, 1] as far as roots go (one root at most each).
    const Expansion g = grid_point(zero, -p[1].estimate() / p[2].scaled(2.0).estimate());
    double at_g = 0.0;
    if (strictly_between(zero, g, one) && sign_at_time(p, g, at_g) == -p[2].sign()) {
      monotone_piece(zero, s_0, at_0, g, -p[2].sign(), at_g);
      monotone_piece(g, -p[2].sign(), at_g, one, s_1, at_1);
      return finish();
    }
  }
  return isolate(p, n, zero, s_0, one, s_1, 0, out);
}

bool not_before(const Candidate& c, double t) {
  if (c.rational) return (c.num - c.den.scaled(t)).sign() >= 0;
  return (c.lo - Expansion(t)).sign() >= 0;
}

}  // namespace clothcd::ccd::detail
