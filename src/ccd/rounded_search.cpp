// The thickness-0 fast tier in floating point with per-query error bounds (see rounded_search.hpp).
//
// The search: the step is subdivided, left half first (so the first hit is the earliest); a piece [t0, t1], given by
// W at its ends, is
//   - cleared when some coordinate of every W box (W's hull over the piece, widened by point_error) has one strict
//     sign, or when that holds for both halves of the piece (checked before the tests below, which could then only
//     clear it), or when D's Bernstein coefficients on the piece have one certain sign (no coplanarity), or, from depth
//     4 on (above it a piece only splits), when in some axis projection every triangle of W has 2D cross products of
//     both certain signs over the whole piece (the origin is outside every triangle, so outside conv W);
//   - a proven hit when D certainly changes sign over the piece (a coplanar instant exists) and, in some projection,
//     one triangle of W has three 2D cross products of the same certain sign over the piece (the origin strictly
//     inside a non-degenerate projected triangle, which at the coplanar instant puts it inside conv W); the time of
//     impact, D's first root in the piece, is then bracketed by de Casteljau halving to within kToiTolerance, and a
//     bracket that cannot be proven that tight leaves the piece undecided.
// A 2D cross product W_a x W_b is quadratic in t; its sign over a piece is certain when its three Bernstein
// coefficients there have one sign beyond their error bound (at least as tight as a product of the W boxes).
//
// Error bounds, u = 2^-53, coordinates at most 2^100 in magnitude (no overflow). Underflow: a rounded product or
// halving may err by 2^-1075 in absolute terms, which the absolute terms below cover. Those terms are normal numbers,
// and magnitudes are at least 2^-500 so that their products stay normal: subnormal operands and results cost about
// 100 cycles each (microcode assists) on common CPUs, and exact zeros are common in W.
//   - A rounded difference x_i - x_j is within 1.01 u of its magnitude (one rounding; exact when subnormal), and its
//     sign is exact. Per coordinate of W's point m, W_max = the larger magnitude of its two rounded ends.
//   - point_at: (1 - t) W(0) + t W(1), 1 - t exact for the dyadic times used: the ends' errors (1.01 u W_max) plus
//     three roundings of at most u W_max each (and underflow): point_error = 4 u W_max + 2^-1022. Both the exact and
//     the rounded W(t) are at most magnitude = W_max (1 + 2^-40) + 2^-500.
//   - cross_coefficients: with x, y, z, w the coordinates of x y - z w, inputs within their point_error e and at most
//     their magnitude P: each product moves by at most P_x e_y + P_y e_x (the middle coefficient halves four products,
//     two products' worth), so 8 u (P_x P_y + P_z P_w) plus at most 4 x 2^102 x 2^-1022 from the absolute terms; the
//     middle coefficient's roundings (four products, three sums, an exact halving) 3 u (P_x P_y + P_z P_w):
//     cross_error = 16 u (P_x P_y + P_z P_w) + 2^-900.
//   - D's tripled coefficients (four cross products shared by six dot products): with A, B, C the larger magnitudes of
//     the edge vectors' rounded components at both ends and P3 = A . (|B| x |C|) (x: the cross product with every
//     term's magnitude added), each determinant is at most P3. The inputs' errors move a determinant by at most
//     3.04 u P3, three determinants' worth per coefficient (9.2 u P3); the roundings of a cross product component are
//     at most 2 u of its magnitude bound, of the mixed sum of two 6 u, of a coefficient's dot products and sums at most
//     20 u P3: d.error = 64 u P3 + 2^-1000.
//   - halve: each new coefficient is an average of two (up to three levels deep), each average adding at most u B
//     (and an underflow), where B bounds every coefficient's magnitude on every piece: the exact ones lie in the hull
//     of the step's (de Casteljau is a convex combination), so B = (max |d.b| + 2 d.error) (1 + 2^-40) holds for the
//     first 2^11 halvings; halving_error = 4 u B + 2^-1000.
// Tests that compare rounded values with their exact rational values: tests/ccd/test_rounded_search.cpp.
#include "ccd/rounded_search.hpp"

#include <algorithm>
#include <cmath>

#include "support/simd.hpp"

namespace clothcd::ccd::detail {

namespace {

using Points = WPoints;

constexpr double kUnitRoundoff = 0x1p-53;
// Coordinates the bounds above hold for.
constexpr double kMaxCoordinate = 0x1p100;
// Thickness 0: pieces down to 2^-4 of the step before the exact tiers. Of the public handcrafted queries that the
// fast tier decided at all (measured when it used interval arithmetic), 91% (VF) / 76% (EE) need no subdivision, all
// but 2 / 13 stay within depth 4 and none goes deeper than 8: what is still undecided at depth 4 is mostly an exact
// touch or a miss by a rounding error, which no subdivision decides, so deeper pieces mostly delay the exact tiers.
constexpr int kMaxDepth = 4;
// Deciding exactly: pieces go on splitting below kMaxDepth while the query has examined fewer than kDeepPieceBudget
// pieces below kMaxDepth. A piece that misses or touches by far more than a rounding error is decided there at a few
// tests per level, instead of by the exact tiers (about 100k instructions a query); what is left (an exact touch, a
// miss by a rounding error, coplanar motion) exhausts the budget quickly and goes to them.
constexpr int kDeepPieceBudget = 8;
// A conservative hit's time of impact is tightened by at most kToiBisections halvings of its piece.
constexpr int kToiBisections = 24;

// W at time t: (1 - t) W(0) + t W(1).
[[gnu::always_inline]] inline void interpolate(const RoundedQuery& query, double t, Points& w) {
  const double s = 1.0 - t;
  for (int d = 0; d < 3; ++d)
    for (int m = 0; m < 4; ++m) w[d][m] = s * query.start[d][m] + t * query.end[d][m];
}

// The Bernstein coefficients of W_a x W_b on the piece from p to q, in the plane of the axes u and v.
[[gnu::always_inline]] inline std::array<double, 3> cross_terms(const Points& p, const Points& q, int a, int b, int u,
                                                                int v) {
  return {p[u][a] * p[v][b] - p[v][a] * p[u][b],
          0.5 * ((p[u][a] * q[v][b] + q[u][a] * p[v][b]) - (p[v][a] * q[u][b] + q[v][a] * p[u][b])),
          q[u][a] * q[v][b] - q[v][a] * q[u][b]};
}

// cross_terms' error bound, from W's magnitudes.
[[gnu::always_inline]] inline double cross_bound(const Points& magnitude, int a, int b, int u, int v) {
  return 16.0 * kUnitRoundoff * (magnitude[u][a] * magnitude[v][b] + magnitude[v][a] * magnitude[u][b]) + 0x1p-900;
}

// De Casteljau halving of a cubic's coefficients; each error grows by added_error.
[[gnu::always_inline]] inline void halve_cubic(const RoundedCubic& cubic, double added_error, RoundedCubic& left,
                                               RoundedCubic& right) {
  const std::array<double, 4>& b = cubic.b;
  const double b01 = 0.5 * (b[0] + b[1]), b12 = 0.5 * (b[1] + b[2]), b23 = 0.5 * (b[2] + b[3]);
  const double b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23);
  const double b0123 = 0.5 * (b012 + b123);
  const double error = cubic.error + added_error;
  left = {{b[0], b01, b012, b0123}, error};
  right = {{b0123, b123, b23, b[3]}, error};
}

int certain_sign(double value, double error) {
  return value > error ? 1 : (value < -error ? -1 : 0);
}

int common_strict_sign(const RoundedCubic& cubic) {
  const int s = certain_sign(cubic.b[0], cubic.error);
  for (int i = 1; i < 4; ++i)
    if (certain_sign(cubic.b[i], cubic.error) != s) return 0;
  return s;
}

// True when the boxes of W over the piece between the points p and q, widened by `error`, exclude the origin: some
// coordinate has one strict sign in every box. Two points per lane pair.
bool boxes_exclude_origin(const Points& p, const Points& q, const Points& error) {
  namespace lanes = simd::baseline_lanes;
  for (int d = 0; d < 3; ++d) {
    lanes::Masks above = lanes::Masks{} == 0, below = above;
    for (int m = 0; m < 4; m += 2) {
      const lanes::Doubles pm{p[d][m], p[d][m + 1]}, qm{q[d][m], q[d][m + 1]}, e{error[d][m], error[d][m + 1]};
      above &= lanes::less(e, lanes::min(pm, qm));
      below &= lanes::less(lanes::max(pm, qm), -e);
    }
    if ((above[0] & above[1]) != 0 || (below[0] & below[1]) != 0) return true;
  }
  return false;
}

enum class TriangleVerdict { Outside, Inside, Unknown };

// `cross[a][b]`: the certain sign of W_a x W_b over the piece (0 when uncertain).
TriangleVerdict classify_triangle(const int (&cross)[4][4], int a, int b, int c) {
  const int s[3] = {cross[a][b], cross[b][c], cross[c][a]};
  const bool positive = s[0] > 0 || s[1] > 0 || s[2] > 0;
  const bool negative = s[0] < 0 || s[1] < 0 || s[2] < 0;
  if (positive && negative) return TriangleVerdict::Outside;
  if (s[0] != 0 && s[0] == s[1] && s[1] == s[2]) return TriangleVerdict::Inside;
  return TriangleVerdict::Unknown;
}

// Clear when in some projection the origin is certainly outside every triangle of W over the whole piece between p
// and q; Hit when D certainly changes sign over the piece and in some projection the origin is certainly strictly
// inside one triangle (then no projection can exclude it: at the coplanar instant the origin is in conv W), so both
// answers end the scan early; else Undecided.
SearchOutcome classify_projections(const RoundedQuery& query, const Points& p, const Points& q, bool d_changes_sign) {
  const int count = query.count;
  bool one_inside = false;
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3;
    const int v = (k + 2) % 3;
    int cross[4][4] = {};
    for (int a = 0; a < count; ++a) {
      for (int b = a + 1; b < count; ++b) {
        const std::array<double, 3> c = cross_terms(p, q, a, b, u, v);
        const double error = cross_bound(query.magnitude, a, b, u, v);
        const int s0 = certain_sign(c[0], error);
        const bool one_sign = s0 == certain_sign(c[1], error) && s0 == certain_sign(c[2], error);
        const int s = one_sign ? s0 : 0;
        cross[a][b] = s;
        cross[b][a] = -s;
      }
    }
    bool all_outside = true;
    for (int a = 0; a < count; ++a) {
      for (int b = a + 1; b < count; ++b) {
        for (int c = b + 1; c < count; ++c) {
          const TriangleVerdict t = classify_triangle(cross, a, b, c);
          all_outside = all_outside && t == TriangleVerdict::Outside;
          one_inside = one_inside || t == TriangleVerdict::Inside;
        }
      }
    }
    if (all_outside) return SearchOutcome::Clear;
    if (one_inside && d_changes_sign) return SearchOutcome::Hit;
  }
  return SearchOutcome::Undecided;
}

// Lower bound of the first root of D in [t0, t1]: the start of the first sub-piece where D is not certainly non-zero.
// `tight` when the bound is proven within kToiTolerance of the first root: D has certain opposite signs at the ends
// of the final sub-piece [lo, t1] with t1 - lo <= kToiTolerance (and none of its roots lies before lo).
struct RootBound {
  double lo = 0.0;
  bool tight = false;
};

RootBound first_root_lower_bound(double t0, double t1, RoundedCubic d, double halving_error) {
  const auto brackets_root = [&d] {
    const int s = certain_sign(d.b[0], d.error);
    return s != 0 && certain_sign(d.b[3], d.error) == -s;
  };
  for (int i = 0; i < kToiBisections; ++i) {
    if (t1 - t0 <= kToiTolerance && brackets_root()) return {t0, true};
    const double mid = 0.5 * (t0 + t1);
    if (!(mid > t0 && mid < t1)) break;
    RoundedCubic left, right;
    halve_cubic(d, halving_error, left, right);
    if (common_strict_sign(left) != 0) {
      t0 = mid;
      d = right;
    } else {
      t1 = mid;
      d = left;
    }
  }
  return {t0, t1 - t0 <= kToiTolerance && brackets_root()};
}

// The two halves of a piece split at `mid`: W there, and whether each half's boxes exclude the origin.
struct Halves {
  Points middle;
  bool left_clear = false, right_clear = false;
};

void split_piece(const RoundedQuery& query, double mid, const Points& e0, const Points& e1, Halves& halves) {
  interpolate(query, mid, halves.middle);
  halves.left_clear = boxes_exclude_origin(e0, halves.middle, query.point_error);
  halves.right_clear = boxes_exclude_origin(halves.middle, e1, query.point_error);
}

struct Search {
  const RoundedQuery& query;
  int deep_pieces_left = 0;  // pieces below kMaxDepth this query may still examine
  double toi = 1.0;
  double until = 1.0;  // pieces starting after this time are not examined
};

// Decides the piece [t0, t1] with ends e0 and e1, whose W boxes do not exclude the origin and on which D is `d`
// (the step's, halved below it).
SearchOutcome search_piece(Search& search, double t0, double t1, const Points& e0, const Points& e1, int depth,
                           const RoundedCubic& d) {
  if (t0 > search.until) return SearchOutcome::Clear;
  const RoundedQuery& query = search.query;
  const double mid = 0.5 * (t0 + t1);
  if (depth > kMaxDepth && common_strict_sign(d) == 0 && --search.deep_pieces_left < 0)
    return SearchOutcome::Undecided;
  const bool can_split = (depth < kMaxDepth || search.deep_pieces_left > 0) && mid > t0 && mid < t1;
  // When both halves' boxes exclude the origin there is no contact in the piece, so the tests below could not find a
  // hit: they would clear the piece or split it into these halves, which clear at once. Either way the piece is clear,
  // without their cost. The whole step's own tests almost never decide, so there the halves come first; deeper, after
  // the Bernstein test, which decides more pieces and needs no middle positions.
  Halves halves;
  const bool halves_first = depth == 0;
  if (can_split && halves_first) {
    split_piece(query, mid, e0, e1, halves);
    if (halves.left_clear && halves.right_clear) return SearchOutcome::Clear;
  }
  if (common_strict_sign(d) != 0) return SearchOutcome::Clear;
  if (can_split && !halves_first) {
    split_piece(query, mid, e0, e1, halves);
    if (halves.left_clear && halves.right_clear) return SearchOutcome::Clear;
  }
  const int sign_start = certain_sign(d.b[0], d.error);
  const int sign_end = certain_sign(d.b[3], d.error);
  // Above kMaxDepth the projection tests rarely decide what the halves would not, so a piece that can split only
  // splits (its halves cover it, earliest first).
  const SearchOutcome verdict = depth < kMaxDepth && can_split
                                    ? SearchOutcome::Undecided
                                    : classify_projections(query, e0, e1, sign_start != 0 && sign_end == -sign_start);
  if (verdict == SearchOutcome::Clear) return SearchOutcome::Clear;
  if (verdict == SearchOutcome::Hit) {
    // Every earlier piece was cleared, and every root of D in this one is a contact.
    const RootBound bound = first_root_lower_bound(t0, t1, d, query.halving_error);
    search.toi = bound.lo;
    return bound.tight ? SearchOutcome::Hit : SearchOutcome::Undecided;
  }
  if (!can_split) {
    // Every earlier piece was cleared, and a contact needs D = 0: none before D's first possible root in this piece.
    search.toi = first_root_lower_bound(t0, t1, d, query.halving_error).lo;
    return SearchOutcome::Undecided;
  }
  RoundedCubic left_d, right_d;
  halve_cubic(d, query.halving_error, left_d, right_d);
  if (!halves.left_clear) {
    const SearchOutcome left = search_piece(search, t0, mid, e0, halves.middle, depth + 1, left_d);
    if (left != SearchOutcome::Clear) return left;
  }
  if (halves.right_clear) return SearchOutcome::Clear;
  return search_piece(search, mid, t1, halves.middle, e1, depth + 1, right_d);
}

using Vector = std::array<double, 3>;

Vector difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vector cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// The cross product's terms' magnitudes added, of vectors of magnitudes.
Vector magnitude_cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] + a[2] * b[1], a[2] * b[0] + a[0] * b[2], a[0] * b[1] + a[1] * b[0]};
}
Vector sum(const Vector& a, const Vector& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
double dot(const Vector& a, const Vector& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
// Per component, the larger magnitude of a and b.
Vector larger_magnitudes(const Vector& a, const Vector& b) {
  return {std::max(std::abs(a[0]), std::abs(b[0])), std::max(std::abs(a[1]), std::abs(b[1])),
          std::max(std::abs(a[2]), std::abs(b[2]))};
}

}  // namespace

bool fits_floating_point_tiers(const CcdQuery& query) {
  for (int i = 0; i < 4; ++i)
    if (!(query.start[i].cwiseAbs().maxCoeff() <= kMaxCoordinate) ||
        !(query.end[i].cwiseAbs().maxCoeff() <= kMaxCoordinate))
      return false;
  return true;
}

std::optional<RoundedQuery> rounded_query(const CcdQuery& query) {
  if (!fits_floating_point_tiers(query)) return std::nullopt;
  RoundedQuery rounded;
  const bool vertex_face = query.kind == PairKind::VertexFace;
  rounded.count = vertex_face ? 3 : 4;
  const auto fill_points = [&](const std::array<Eigen::Vector3d, 4>& x, Points& w) {
    for (int d = 0; d < 3; ++d) {
      if (vertex_face) {
        w[d] = {x[0][d] - x[1][d], x[0][d] - x[2][d], x[0][d] - x[3][d], x[0][d] - x[1][d]};
      } else {
        w[d] = {x[0][d] - x[2][d], x[0][d] - x[3][d], x[1][d] - x[2][d], x[1][d] - x[3][d]};
      }
    }
  };
  fill_points(query.start, rounded.start);
  fill_points(query.end, rounded.end);
  // D's edge vectors from x0 at both ends.
  std::array<Vector, 3> e0, e1;
  for (int i = 0; i < 3; ++i) {
    e0[i] = difference(query.start[i + 1], query.start[0]);
    e1[i] = difference(query.end[i + 1], query.end[0]);
  }
  for (int d = 0; d < 3; ++d) {
    for (int m = 0; m < 4; ++m) {
      const double w_max = std::max(std::abs(rounded.start[d][m]), std::abs(rounded.end[d][m]));
      rounded.point_error[d][m] = 4.0 * kUnitRoundoff * w_max + 0x1p-1022;
      rounded.magnitude[d][m] = w_max * (1.0 + 0x1p-40) + 0x1p-500;
    }
  }
  // D is trilinear in its edge vectors (a, b, c), so its tripled Bernstein coefficients are a0.(b0 x c0) times 3,
  // a1.(b0 x c0) + a0.(b1 x c0 + b0 x c1), and so on: four cross products shared by six dot products.
  const Vector bc00 = cross(e0[1], e0[2]), bc11 = cross(e1[1], e1[2]);
  const Vector bc_mixed = sum(cross(e1[1], e0[2]), cross(e0[1], e1[2]));
  rounded.d.b = {3.0 * dot(e0[0], bc00), dot(e1[0], bc00) + dot(e0[0], bc_mixed),
                 dot(e1[0], bc_mixed) + dot(e0[0], bc11), 3.0 * dot(e1[0], bc11)};
  const Vector a = larger_magnitudes(e0[0], e1[0]), b = larger_magnitudes(e0[1], e1[1]);
  const double p3 = dot(a, magnitude_cross(b, larger_magnitudes(e0[2], e1[2])));
  rounded.d.error = 64.0 * kUnitRoundoff * p3 + 0x1p-1000;
  double largest = 0.0;
  for (const double b : rounded.d.b) largest = std::max(largest, std::abs(b));
  rounded.halving_error = 4.0 * kUnitRoundoff * (largest + 2.0 * rounded.d.error) * (1.0 + 0x1p-40) + 0x1p-1000;
  return rounded;
}

void point_at(const RoundedQuery& query, double t, Points& w) {
  interpolate(query, t, w);
}

std::array<double, 3> cross_coefficients(const Points& p, const Points& q, int a, int b, int k) {
  return cross_terms(p, q, a, b, (k + 1) % 3, (k + 2) % 3);
}

double cross_error(const RoundedQuery& query, int a, int b, int k) {
  return cross_bound(query.magnitude, a, b, (k + 1) % 3, (k + 2) % 3);
}

void halve(const RoundedCubic& cubic, double added_error, RoundedCubic& left, RoundedCubic& right) {
  halve_cubic(cubic, added_error, left, right);
}

SearchAnswer search_step(const RoundedQuery& query, bool deep, double until) {
  Search search{query, deep ? kDeepPieceBudget : 0, 1.0, until};
  if (boxes_exclude_origin(query.start, query.end, query.point_error)) return {};
  const SearchOutcome outcome = search_piece(search, 0.0, 1.0, query.start, query.end, 0, query.d);
  return {outcome, outcome == SearchOutcome::Clear ? 1.0 : search.toi};
}

bool possible_touch_at(const RoundedQuery& query, int end) {
  const double d_at_end = end == 0 ? query.d.b[0] : query.d.b[3];
  if (certain_sign(d_at_end, query.d.error) != 0) return false;
  const Points& w = end == 0 ? query.start : query.end;
  // The end points' signs are exact: no margin.
  static constexpr Points kExact{};
  return !boxes_exclude_origin(w, w, kExact) &&
         classify_projections(query, w, w, false) != SearchOutcome::Clear;
}

bool has_zero_point(const RoundedQuery& query, int end) {
  const Points& w = end == 0 ? query.start : query.end;
  for (int m = 0; m < query.count; ++m)
    if (w[0][m] == 0.0 && w[1][m] == 0.0 && w[2][m] == 0.0) return true;
  return false;
}

bool outside_before_end(const RoundedQuery& query) {
  for (int d = 0; d < 3; ++d) {
    bool above = true;
    bool below = true;
    for (int m = 0; m < query.count; ++m) {
      above = above && query.start[d][m] > 0.0 && query.end[d][m] >= 0.0;
      below = below && query.start[d][m] < 0.0 && query.end[d][m] <= 0.0;
    }
    if (above || below) return true;
  }
  return false;
}

}  // namespace clothcd::ccd::detail
