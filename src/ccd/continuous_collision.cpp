// The fast, safe CCD narrow phase (section 2.2's coplanarity cubic, made exact-safe).
//
// Both pair kinds are one question: is the origin in conv W(t) for some t in [0, 1], with W = {v - f_i} (vertex-face)
// or W = {a_i - b_j} (edge-edge), all linear in t (see exact_reference.cpp for why this is equivalent). The time range
// is subdivided (left half first, so the first hit is the earliest); on each piece [t0, t1], with outward-rounded
// interval arithmetic (W at a piece end from W at the step's ends, D's Bernstein coefficients on a piece by halving
// its parent's):
//   - cleared when some coordinate of every W box has one strict sign (the origin is outside the boxes' hull), or
//     when that holds for both halves of the piece (checked before the tests below, which could then only clear it),
//     or when the Bernstein coefficients of D(t) = det(x1 - x0, x2 - x0, x3 - x0) on the piece have one strict sign
//     (no coplanarity), or, from depth 4 on (above it a piece only splits), when in some axis projection every
//     triangle of W has 2D cross products of both strict signs (the origin is outside every triangle, so outside
//     conv W);
//   - proven hit when D certainly changes sign over the piece (a coplanar instant exists) and, in some projection,
//     one triangle of W has three 2D cross products of the same strict sign (a non-degenerate projected triangle with
//     the origin strictly inside, which at the coplanar instant puts the origin inside conv W); the time of impact,
//     D's first root in the piece, is then bracketed by de Casteljau halving to within 2^-21 of the step, and a
//     bracket that cannot be proven that tight leaves the piece undecided.
// Undecided pieces split on to depth 4, and with CcdSettings::decide_exactly deeper within a budget of pieces; a
// query still undecided then goes to the exact expansion tier (expansion_collision.cpp), and what that cannot decide
// to the exact rational reference, so no collision is ever missed and every hit is proven; before them, a query whose
// primitives share a coordinate plane for the whole step (two points of W pinned to it, pinned_segment_contact.hpp)
// is decided on that plane, where it is a segment test that intervals can prove. A possible exact touch at
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
#include "ccd/interval.hpp"
#include "ccd/pinned_segment_contact.hpp"
#include "ccd/thickness_contact.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd {

namespace {

using detail::certain_sign;
using detail::Interval;

// Thickness 0: pieces down to 2^-4 of the step before the exact tiers. Of the public handcrafted queries that the
// intervals decide at all, 91% (VF) / 76% (EE) need no subdivision, all but 2 / 13 stay within depth 4 and none goes
// deeper than 8: what is still undecided at depth 4 is mostly an exact touch or a miss by a rounding error, which no
// subdivision decides, so deeper pieces mostly delay the exact tiers (instructions per query with the combined
// filter, VF / EE: depth 8 4501 / 4828, depth 4 4168 / 4589, depth 3 4094 / 4622, depth 2 4035 / 4650; 16 levels were
// 12% above 8). Reporting the undecided queries as conservative hits instead, depths 2 / 4 / 6 / 8 leave 42 / 40 / 40 /
// 39 false positives (VF) and 72 / 62 / 55 / 53 (EE) on those queries, the deeper ones 10-25% slower than depth 4.
constexpr int kMaxDepth = 4;
// Deciding exactly: pieces go on splitting below kMaxDepth while the query has examined fewer than kDeepPieceBudget
// pieces below kMaxDepth (the approximate mode has no such budget). A piece that misses or touches by far more than a
// rounding error is decided there at a few interval tests per level, instead of by the exact tiers (about 100k
// instructions a query); what is left (an exact touch, a miss by a rounding error, coplanar motion) exhausts the budget
// quickly and goes to them. (Rod-twist: 1,711 queries of 19k reach the exact tiers at depth 4, 183 with this budget;
// budgets of 16 and 24 decide a few more there but cost more on cloth-funnel's exact touches.)
constexpr int kDeepPieceBudget = 8;
// A hit's time of impact is a lower bound proven within kToiTolerance of the earliest contact (else the exact tiers
// give it); a conservative hit's is tightened by at most kToiBisections halvings of its piece.
constexpr double kToiTolerance = 0x1p-21;
constexpr int kToiBisections = 24;
// Beyond this magnitude intermediate products could overflow; such queries go straight to the exact reference.
constexpr double kMaxFastCoordinate = 0x1p100;

struct IVec {
  Interval c[3];
};

[[gnu::always_inline]] inline IVec operator-(const IVec& a, const IVec& b) {
  return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}};
}
[[gnu::always_inline]] inline IVec operator+(const IVec& a, const IVec& b) {
  return {{a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]}};
}
[[gnu::always_inline]] inline IVec hull(const IVec& a, const IVec& b) {
  return {{detail::hull(a.c[0], b.c[0]), detail::hull(a.c[1], b.c[1]), detail::hull(a.c[2], b.c[2])}};
}
[[gnu::always_inline]] inline IVec cross(const IVec& a, const IVec& b) {
  return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2], a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}
[[gnu::always_inline]] inline Interval dot(const IVec& a, const IVec& b) {
  return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2];
}

using Positions = std::array<IVec, 4>;

// The four points at the start (t = 0) or the end (t = 1) of the step, exactly.
void end_positions(const std::array<Eigen::Vector3d, 4>& points, Positions& x) {
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) x[i].c[d] = detail::exact(points[i][d]);
}

struct PointSet {
  IVec w[4];
  int count = 0;
};

void difference_points(PairKind kind, const Positions& x, PointSet& set) {
  set.count = 0;
  if (kind == PairKind::VertexFace) {
    for (int j = 1; j < 4; ++j) set.w[set.count++] = x[0] - x[j];
  } else {
    for (int i = 0; i < 2; ++i)
      for (int j = 2; j < 4; ++j) set.w[set.count++] = x[i] - x[j];
  }
}

// D's ingredients on the step, whose end positions are x0 and x1: the edge vectors from x[0] at both ends and their
// end cross products, from which D at the ends follows (what a touch at t = 0 or 1 needs) and its middle Bernstein
// coefficients.
struct DetParts {
  IVec a0, b0, c0, a1, b1, c1, bc00, bc11;
};

DetParts det_parts(const Positions& x0, const Positions& x1) {
  DetParts p;
  p.a0 = x0[1] - x0[0];
  p.b0 = x0[2] - x0[0];
  p.c0 = x0[3] - x0[0];
  p.a1 = x1[1] - x1[0];
  p.b1 = x1[2] - x1[0];
  p.c1 = x1[3] - x1[0];
  p.bc00 = cross(p.b0, p.c0);
  p.bc11 = cross(p.b1, p.c1);
  return p;
}

// Bernstein coefficients of D on the step (the middle two times 3). D is trilinear in (a, b, c), so they are
// a0.(b0 x c0), a1.(b0 x c0) + a0.(b1 x c0 + b0 x c1), and so on: four cross products shared by the six dot products
// (interval arithmetic is subdistributive: no wider than the ten determinants, up to rounding).
std::array<Interval, 4> bernstein_of_d(const DetParts& p) {
  const IVec bc_mixed = cross(p.b1, p.c0) + cross(p.b0, p.c1);
  return {dot(p.a0, p.bc00), dot(p.a1, p.bc00) + dot(p.a0, bc_mixed), dot(p.a1, bc_mixed) + dot(p.a0, p.bc11),
          dot(p.a1, p.bc11)};
}

int common_strict_sign(const std::array<Interval, 4>& b) {
  const int s = certain_sign(b[0]);
  for (int i = 1; i < 4; ++i)
    if (certain_sign(b[i]) != s) return 0;
  return s;
}

bool boxes_exclude_origin(const PointSet& boxes, double margin) {
  for (int d = 0; d < 3; ++d) {
    bool all_above = true;
    bool all_below = true;
    for (int m = 0; m < boxes.count; ++m) {
      all_above = all_above && boxes.w[m].c[d].lo > margin;
      all_below = all_below && boxes.w[m].c[d].hi < -margin;
    }
    if (all_above || all_below) return true;
  }
  return false;
}

// Certain signs of the 2D cross products W[a] x W[b] (a < b) in the projection dropping axis k.
struct ProjectedSigns {
  int cross[4][4] = {};
};

ProjectedSigns projected_signs(const PointSet& boxes, int k) {
  const int u = (k + 1) % 3;
  const int v = (k + 2) % 3;
  ProjectedSigns signs;
  for (int a = 0; a < boxes.count; ++a) {
    for (int b = a + 1; b < boxes.count; ++b) {
      const int s = certain_sign(boxes.w[a].c[u] * boxes.w[b].c[v] - boxes.w[a].c[v] * boxes.w[b].c[u]);
      signs.cross[a][b] = s;
      signs.cross[b][a] = -s;
    }
  }
  return signs;
}

enum class TriangleVerdict { Outside, Inside, Unknown };

TriangleVerdict classify_triangle(const ProjectedSigns& signs, int a, int b, int c) {
  const int s[3] = {signs.cross[a][b], signs.cross[b][c], signs.cross[c][a]};
  const bool positive = s[0] > 0 || s[1] > 0 || s[2] > 0;
  const bool negative = s[0] < 0 || s[1] < 0 || s[2] < 0;
  if (positive && negative) return TriangleVerdict::Outside;
  if (s[0] != 0 && s[0] == s[1] && s[1] == s[2]) return TriangleVerdict::Inside;
  return TriangleVerdict::Unknown;
}

enum class PieceOutcome { Clear, Hit, Undecided };

// Clear when in some projection the origin is certainly outside every triangle of W; Hit when D certainly changes
// sign over the piece and in some projection the origin is certainly strictly inside one triangle (then no projection
// can exclude it: at the coplanar instant the origin is in conv W), so both answers end the scan early; else
// Undecided.
PieceOutcome classify_projections(const PointSet& boxes, bool d_changes_sign) {
  bool one_inside = false;
  for (int k = 0; k < 3; ++k) {
    const ProjectedSigns signs = projected_signs(boxes, k);
    bool all_outside = true;
    for (int a = 0; a < boxes.count; ++a) {
      for (int b = a + 1; b < boxes.count; ++b) {
        for (int c = b + 1; c < boxes.count; ++c) {
          const TriangleVerdict t = classify_triangle(signs, a, b, c);
          all_outside = all_outside && t == TriangleVerdict::Outside;
          one_inside = one_inside || t == TriangleVerdict::Inside;
        }
      }
    }
    if (all_outside) return PieceOutcome::Clear;
    if (one_inside && d_changes_sign) return PieceOutcome::Hit;
  }
  return PieceOutcome::Undecided;
}

// True when D (d_at_end, its enclosure there) may vanish at the step's end, where W is w, and the origin may be in
// conv W there: pieces ending there can never be decided by intervals (an exact touch at t = 0 or 1), so the exact
// tiers decide the query at once.
bool undecidable_end(const PointSet& w, const Interval& d_at_end) {
  if (certain_sign(d_at_end) != 0) return false;
  return !boxes_exclude_origin(w, 0.0) && classify_projections(w, false) != PieceOutcome::Clear;
}

// True when a point of W is exactly the origin (a vertex on a face's corner, two edges sharing an end point): the
// origin is then in conv W.
bool has_zero_point(const PointSet& w) {
  for (int m = 0; m < w.count; ++m) {
    bool zero = true;
    for (int d = 0; d < 3; ++d) zero = zero && w.w[m].c[d].lo == 0.0 && w.w[m].c[d].hi == 0.0;
    if (zero) return true;
  }
  return false;
}

// True when the origin is certainly outside conv W(t) for every t in [0, 1): some coordinate is of one strict sign at
// t = 0 and of that sign or zero at t = 1 for every point of W (start and end), so W(t), a convex combination with a
// positive weight on W(0), keeps that strict sign before the end. A touch at the end then is the only possible contact:
// a cloth collapsing to a point, an edge ending exactly on a face, which no interval piece ending at 1 could decide.
bool outside_before_end(const PointSet& start, const PointSet& end) {
  for (int d = 0; d < 3; ++d) {
    bool above = true;
    bool below = true;
    for (int m = 0; m < start.count; ++m) {
      above = above && start.w[m].c[d].lo > 0.0 && end.w[m].c[d].lo >= 0.0;
      below = below && start.w[m].c[d].hi < 0.0 && end.w[m].c[d].hi <= 0.0;
    }
    if (above || below) return true;
  }
  return false;
}

// W over the step: W(t) = W(0) + t (W(1) - W(0)), each difference point linear in t. Its enclosures at the step's ends
// come from the exact end positions, so W(0) + t (W(1) - W(0)) encloses W(t) in interval arithmetic (both terms
// enclose their real values); each piece end's W is computed once, shared by the two pieces that meet there.
struct Motion {
  PointSet start;
  IVec change[4];
};

Motion motion_of(const PointSet& start, const PointSet& end) {
  Motion motion{start, {}};
  for (int m = 0; m < start.count; ++m) motion.change[m] = end.w[m] - start.w[m];
  return motion;
}

void w_at(const Motion& motion, double t, PointSet& w) {
  w.count = motion.start.count;
  for (int m = 0; m < w.count; ++m)
    for (int d = 0; d < 3; ++d) w.w[m].c[d] = motion.start.w[m].c[d] + detail::scaled(motion.change[m].c[d], t);
}

struct Search {
  const Motion& motion;
  int deep_pieces_left = 0;  // pieces below kMaxDepth this query may still examine
  double toi = 1.0;
  double until = 1.0;  // pieces starting after this time are not examined (continuous_collision_until)
};

// Three times D's Bernstein coefficients on a piece (bernstein_of_d's middle coefficients carry the binomial factor 3,
// so its ends are tripled): signs and sign changes are those of the coefficients.
using TripledBernstein = std::array<Interval, 4>;

TripledBernstein tripled(const std::array<Interval, 4>& of_piece) {
  return {detail::scaled(of_piece[0], 3.0), of_piece[1], of_piece[2], detail::scaled(of_piece[3], 3.0)};
}

// The coefficients of the piece's two halves by de Casteljau halving in interval arithmetic (a positive combination,
// so the enclosures stay rigorous), without recomputing positions.
void halve(const TripledBernstein& b, TripledBernstein& left, TripledBernstein& right) {
  using detail::scaled;
  const Interval b01 = scaled(b[0] + b[1], 0.5), b12 = scaled(b[1] + b[2], 0.5), b23 = scaled(b[2] + b[3], 0.5);
  const Interval b012 = scaled(b01 + b12, 0.5), b123 = scaled(b12 + b23, 0.5);
  const Interval b0123 = scaled(b012 + b123, 0.5);
  left = {b[0], b01, b012, b0123};
  right = {b0123, b123, b23, b[3]};
}

// Lower bound of the first root of D in [t0, t1]: the start of the first sub-piece where D is not certainly non-zero.
// `tight` when the bound is proven within kToiTolerance of the first root: D has certain opposite signs at the ends
// of the final sub-piece [lo, t1] with t1 - lo <= kToiTolerance (and none of its roots lies before lo).
struct RootBound {
  double lo = 0.0;
  bool tight = false;
};

RootBound first_root_lower_bound(double t0, double t1, TripledBernstein b) {
  const auto brackets_root = [&b] {
    const int s = certain_sign(b[0]);
    return s != 0 && certain_sign(b[3]) == -s;
  };
  for (int i = 0; i < kToiBisections; ++i) {
    if (t1 - t0 <= kToiTolerance && brackets_root()) return {t0, true};
    const double mid = 0.5 * (t0 + t1);
    if (!(mid > t0 && mid < t1)) break;
    TripledBernstein left, right;
    halve(b, left, right);
    if (common_strict_sign(left) != 0) {
      t0 = mid;
      b = right;
    } else {
      t1 = mid;
      b = left;
    }
  }
  return {t0, t1 - t0 <= kToiTolerance && brackets_root()};
}

// The boxes of W over a piece: each difference point's hull over the piece's two ends.
PointSet piece_boxes(const PointSet& e0, const PointSet& e1) {
  PointSet boxes;
  boxes.count = e0.count;
  for (int m = 0; m < e0.count; ++m) boxes.w[m] = hull(e0.w[m], e1.w[m]);
  return boxes;
}

// The two halves of a piece split at `mid`: the middle end and each half's boxes, and whether they exclude the origin.
struct Halves {
  PointSet middle;
  PointSet left_boxes, right_boxes;
  bool left_clear = false, right_clear = false;
};

void split_piece(const Motion& motion, double mid, const PointSet& e0, const PointSet& e1, Halves& halves) {
  w_at(motion, mid, halves.middle);
  halves.left_boxes = piece_boxes(e0, halves.middle);
  halves.right_boxes = piece_boxes(halves.middle, e1);
  halves.left_clear = boxes_exclude_origin(halves.left_boxes, 0.0);
  halves.right_clear = boxes_exclude_origin(halves.right_boxes, 0.0);
}

// Decides the piece [t0, t1] with ends e0 and e1, whose W boxes `boxes` do not exclude the origin and on which D has
// the coefficients `bernstein` (computed from the positions on the whole step, by halving the parent's below it).
PieceOutcome search_exact_contact(Search& search, double t0, double t1, const PointSet& e0, const PointSet& e1,
                                  const PointSet& boxes, int depth, const TripledBernstein& bernstein) {
  if (t0 > search.until) return PieceOutcome::Clear;
  const double mid = 0.5 * (t0 + t1);
  if (depth > kMaxDepth && common_strict_sign(bernstein) == 0 && --search.deep_pieces_left < 0)
    return PieceOutcome::Undecided;
  const bool can_split = (depth < kMaxDepth || search.deep_pieces_left > 0) && mid > t0 && mid < t1;
  // When both halves' boxes exclude the origin there is no contact in the piece, so the tests below could not find a
  // hit: they would clear the piece or split it into these halves, which clear at once. Either way the piece is clear,
  // without their cost. The whole step's own tests almost never decide, so there the halves come first; deeper, after
  // the Bernstein test, which decides more pieces and needs no middle positions.
  Halves halves;
  const bool halves_first = depth == 0;
  if (can_split && halves_first) {
    split_piece(search.motion, mid, e0, e1, halves);
    if (halves.left_clear && halves.right_clear) return PieceOutcome::Clear;
  }
  if (common_strict_sign(bernstein) != 0) return PieceOutcome::Clear;
  if (can_split && !halves_first) {
    split_piece(search.motion, mid, e0, e1, halves);
    if (halves.left_clear && halves.right_clear) return PieceOutcome::Clear;
  }
  const int sign_start = certain_sign(bernstein[0]);
  const int sign_end = certain_sign(bernstein[3]);
  // Above kMaxDepth the projection tests rarely decide what the halves would not, so a piece that can split only splits
  // (its halves cover it, earliest first): rod-twist's exact stage takes 20% fewer instructions.
  const PieceOutcome verdict = depth < kMaxDepth && can_split
                                   ? PieceOutcome::Undecided
                                   : classify_projections(boxes, sign_start != 0 && sign_end == -sign_start);
  if (verdict == PieceOutcome::Clear) return PieceOutcome::Clear;
  if (verdict == PieceOutcome::Hit) {
    // Every earlier piece was cleared, and every root of D in this one is a contact.
    const RootBound bound = first_root_lower_bound(t0, t1, bernstein);
    search.toi = bound.lo;
    return bound.tight ? PieceOutcome::Hit : PieceOutcome::Undecided;
  }
  if (!can_split) {
    // Every earlier piece was cleared, and a contact needs D = 0: none before D's first possible root in this piece.
    search.toi = first_root_lower_bound(t0, t1, bernstein).lo;
    return PieceOutcome::Undecided;
  }
  TripledBernstein left_bernstein, right_bernstein;
  halve(bernstein, left_bernstein, right_bernstein);
  if (!halves.left_clear) {
    const PieceOutcome left =
        search_exact_contact(search, t0, mid, e0, halves.middle, halves.left_boxes, depth + 1, left_bernstein);
    if (left != PieceOutcome::Clear) return left;
  }
  if (halves.right_clear) return PieceOutcome::Clear;
  return search_exact_contact(search, mid, t1, halves.middle, e1, halves.right_boxes, depth + 1, right_bernstein);
}

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

bool fits_fast_path(const CcdQuery& query) {
  for (int i = 0; i < 4; ++i)
    if (!(query.start[i].cwiseAbs().maxCoeff() <= kMaxFastCoordinate) ||
        !(query.end[i].cwiseAbs().maxCoeff() <= kMaxFastCoordinate))
      return false;
  return true;
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
  Eigen::Vector3d normal;
  Eigen::Vector3d towards_first;
  if (query.kind == PairKind::VertexFace) {
    const Eigen::Vector3d e1 = x[2] - x[1];
    const Eigen::Vector3d e2 = x[3] - x[1];
    const Eigen::Vector3d r = x[0] - x[1];
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    if (det > 0.0) {
      const double w1 = (d22 * e1.dot(r) - d12 * e2.dot(r)) / det;
      const double w2 = (d11 * e2.dot(r) - d12 * e1.dot(r)) / det;
      result.parameters = {w1, w2};
    }
    normal = e1.cross(e2);
    towards_first = start[0] - start[1];
  } else {
    const Eigen::Vector3d da = x[1] - x[0];
    const Eigen::Vector3d db = x[3] - x[2];
    const Eigen::Vector3d r = x[0] - x[2];
    const double a = da.dot(da), b = da.dot(db), c = db.dot(db), d = da.dot(r), e = db.dot(r);
    const double det = a * c - b * b;
    if (det > 0.0) {
      const double s = std::clamp((b * e - c * d) / det, 0.0, 1.0);
      const double u = std::clamp((a * e - b * d) / det, 0.0, 1.0);
      result.parameters = {s, u};
    }
    normal = da.cross(db);
    towards_first = (start[0] + start[1]) - (start[2] + start[3]);
  }
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  normal /= length;
  result.normal = normal.dot(towards_first) < 0.0 ? -normal : normal;
}

CcdResult make_hit(const CcdQuery& query, double toi, CcdState state) {
  CcdResult result;
  result.hit = true;
  result.toi = toi;
  result.state = state;
  fill_contact_geometry(query, result);
  return result;
}

// Thickness 0. Queries the intervals leave undecided are reported as conservative hits unless decide_exactly; those
// too large for the fast path always go to the exact tiers. A query that certainly has no contact until `until` is
// separated (see continuous_collision_until).
CcdResult contact_without_thickness(const CcdQuery& query, bool decide_exactly, bool nonpenetration_checked,
                                    double until) {
  if (!nonpenetration_checked && nonpenetration_filter_culls(query)) return CcdResult{};
  if (fits_fast_path(query)) {
    double undecided_from = 0.0;  // lower bound of the earliest contact when undecided
    Positions x0, x1;
    end_positions(query.start, x0);
    end_positions(query.end, x1);
    PointSet start, end;
    difference_points(query.kind, x0, start);
    difference_points(query.kind, x1, end);
    // D at t = 0 and 1 from the whole step's parts, which the first piece reuses.
    const DetParts parts = det_parts(x0, x1);
    const bool touch_at_start = undecidable_end(start, dot(parts.a0, parts.bc00));
    const bool touch_at_end = undecidable_end(end, dot(parts.a1, parts.bc11));
    if (touch_at_start || (touch_at_end && outside_before_end(start, end))) {
      // A touch at the start is the earliest contact; one at the end is the only contact when there is none before.
      const int at = touch_at_start ? 0 : 1;
      const std::optional<bool> touches =
          has_zero_point(at == 0 ? start : end) ? std::optional<bool>(true) : detail::touches_at_step_end(query, at);
      if (at == 1 && until < 1.0) return CcdResult{};  // the touch at the end is the only contact
      if (touches && *touches) return make_hit(query, at, CcdState::Hit);
      if (touches && at == 1) return CcdResult{};
    } else if (!touch_at_end) {
      const Motion motion = motion_of(start, end);
      Search search{motion, decide_exactly ? kDeepPieceBudget : 0, 1.0, until};
      const PointSet boxes = piece_boxes(start, end);
      const PieceOutcome outcome =
          boxes_exclude_origin(boxes, 0.0)
              ? PieceOutcome::Clear
              : search_exact_contact(search, 0.0, 1.0, start, end, boxes, 0, tripled(bernstein_of_d(parts)));
      if (outcome == PieceOutcome::Clear) return CcdResult{};
      if (outcome == PieceOutcome::Hit) return make_hit(query, search.toi, CcdState::Hit);
      undecided_from = search.toi;
      // No contact before undecided_from, so the exact tiers' time of impact (at most kToiTolerance below the contact)
      // would come after `until`.
      if (undecided_from - kToiTolerance > until) return CcdResult{};
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
  if (fits_fast_path(query)) return detail::thick_contact(query, settings.thickness);
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
