// The middle tier of the thickness-0 CCD: the exact reference's decision procedure (exact_reference.cpp) with
// floating-point expansions instead of GMP rationals, for the queries the floating-point fast tier cannot decide
// (contacts exactly at t = 0 or 1, touching or missing by a rounding error at the coplanarity instant, motion coplanar
// for the whole step, ...).
//
// Same question: is the origin in conv W(t) at a root t of D(t) = det(x1 - x0, x2 - x0, x3 - x0)? All polynomials
// (D, and the 2D cross and dot products of W in the three axis projections) get exact expansion coefficients
// (expansion_polynomial.cpp). The coordinates are first scaled by a power of two (no sign changes) below 1 in
// magnitude; when they then lie on the dyadic grid 2^-180 and every time used lies on the grid 2^-150, every exact
// intermediate value (at most degree 3 in coordinates and times) is a multiple of 2^-990, so no expansion operation
// underflows and all signs are exact. Higher-degree values are range-checked first.
//   - Roots of D in [0, 1], and the sign of a polynomial at a bracketed root: expansion_roots.cpp.
//   - A bracketed root where some sign is not filtered out is first tried as an exact rational time: the root of a
//     linear D (or sign polynomial), or a time where two points have the same coordinate on one axis and D vanishes
//     (the sliding and axis-aligned touching contacts). Signs at a rational time are exact homogeneous sums.
//   - D identically zero (coplanar for the whole step): t = 0 first, then 1 and every root of every sign polynomial,
//     earliest first (their roots bracketed by expansion_roots.cpp).
// Signs are filtered first (double or interval arithmetic with a rigorous error bound), expansions only when the
// filter cannot decide. The predicate at each candidate is the reference's (at t = 0 and 1 straight from the end
// positions). The tier gives up (nullopt) when a sign stays undecided (a multiple root of D, a sign that needs a
// quotient or remainder above degree 1), an exact value gets too long or too wide for the double exponent range, or
// the coordinates span too many orders of magnitude; the caller then runs the GMP reference.
#include "ccd/expansion_collision.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <vector>

#include "ccd/expansion_polynomial.hpp"
#include "ccd/expansion_roots.hpp"
#include "ccd/projected_triangle.hpp"
#include "geometry/expansion.hpp"

namespace clothcd::ccd::detail {

namespace {

constexpr int kMaxSpanBits = 180;  // binary orders of magnitude between the largest and the finest coordinate bit

// The query's coordinates times one power of two, all below 1 in magnitude and on the grid 2^-kMaxSpanBits.
std::optional<std::array<std::array<double, 3>, 8>> scaled_coordinates(const CcdQuery& query) {
  std::array<std::array<double, 3>, 8> c;
  int top = INT_MIN, bottom = INT_MAX;
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x = i < 4 ? query.start[i][k] : query.end[i - 4][k];
      c[i][k] = x;
      if (x == 0.0) continue;
      if (!std::isfinite(x)) return std::nullopt;
      int exponent = 0;
      const double mantissa = std::frexp(x, &exponent);  // x = mantissa 2^exponent, 1/2 <= |mantissa| < 1
      auto bits = static_cast<long long>(std::fabs(std::ldexp(mantissa, 53)));
      int lowest = exponent - 53;
      while ((bits & 1) == 0) {
        bits >>= 1;
        ++lowest;
      }
      top = std::max(top, exponent);
      bottom = std::min(bottom, lowest);
    }
  }
  if (top == INT_MIN) return c;
  if (top - bottom > kMaxSpanBits) return std::nullopt;
  for (auto& point : c)
    for (double& x : point) x = std::ldexp(x, -top);
  return c;
}

using PolyVector = std::array<Poly, 3>;

PolyVector operator-(const PolyVector& a, const PolyVector& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Poly determinant(const PolyVector& a, const PolyVector& b, const PolyVector& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The sign system: D and, built on first use, the 2D cross and dot products of W in every axis projection; signs at
// the step's ends also straight from the end positions.
class System {
 public:
  System(PairKind kind, const std::array<std::array<double, 3>, 8>& c) : c_(c) {
    std::array<PolyVector, 4> x;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) x[i][k] = {Expansion(c[i][k]), Expansion::difference(c[i + 4][k], c[i][k])};
    edges_ = {x[1] - x[0], x[2] - x[0], x[3] - x[0]};
    const auto add = [&](int i, int j) {
      pairs_[static_cast<std::size_t>(points_)] = {i, j};
      w_[static_cast<std::size_t>(points_++)] = x[i] - x[j];
    };
    if (kind == PairKind::VertexFace) {
      for (int j = 1; j < 4; ++j) add(0, j);
    } else {
      for (int i = 0; i < 2; ++i)
        for (int j = 2; j < 4; ++j) add(i, j);
    }
    store_.reserve(static_cast<std::size_t>(3 * points_ * points_ + 3));
  }
  // Exact signs of the 2D cross (a < b) and dot products of W[a], W[b] in the projection dropping axis k at the
  // step's start (end = 0) or end (end = 1), from those positions directly (no polynomial built or evaluated).
  int end_cross(int end, int k, int a, int b) const { return end_cross_value(end, k, a, b).sign(); }
  int end_dot(int end, int k, int a, int b) const {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    return (w_at(end, a, u) * w_at(end, b, u) + w_at(end, a, v) * w_at(end, b, v)).sign();
  }
  // The time when points i and j have the same coordinate on axis k, rounded (NaN or infinite when they move in
  // parallel, far off when the difference of their speeds cancels).
  double alignment_time_estimate(int i, int j, int k) const {
    return (c_[j][k] - c_[i][k]) / ((c_[i + 4][k] - c_[i][k]) - (c_[j + 4][k] - c_[j][k]));
  }
  // The same time exactly, num / den with den > 0; false when they move in parallel.
  bool alignment_time(int i, int j, int k, Expansion& num, Expansion& den) const {
    num = Expansion::difference(c_[j][k], c_[i][k]);
    den = Expansion::difference(c_[i + 4][k], c_[i][k]) - Expansion::difference(c_[j + 4][k], c_[j][k]);
    if (den.is_zero()) return false;
    if (den.sign() < 0) {
      num = -num;
      den = -den;
    }
    return true;
  }
  // D, built on first use.
  const Poly& d() {
    if (!d_built_) d_ = determinant(edges_[0], edges_[1], edges_[2]);
    d_built_ = true;
    return d_;
  }
  // The exact sign of D at the step's start (end = 0) or end (end = 1), from those positions.
  int end_d_sign(int end) const {
    std::array<std::array<Expansion, 3>, 3> e;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) e[i][k] = Expansion::difference(c_[4 * end + i + 1][k], c_[4 * end][k]);
    const auto minor = [&](int u, int v) { return e[1][u] * e[2][v] - e[1][v] * e[2][u]; };
    return (e[0][0] * minor(1, 2) - e[0][1] * minor(0, 2) + e[0][2] * minor(0, 1)).sign();
  }
  // The exact sign of the normal component N_k (see normal()) at the step's start (end = 0) or end (end = 1).
  int end_normal_sign(int end, int k) const {
    return (end_cross_value(end, k, 0, 1) + end_cross_value(end, k, 1, 2) - end_cross_value(end, k, 0, 2)).sign();
  }
  int points() const { return points_; }
  // The axes ordered by decreasing magnitude of the rounded normal of W's plane at time t: the projection dropping the
  // first is the best conditioned (estimates only, the order does not change the answer).
  std::array<int, 3> axes_by_normal(double t) const {
    std::array<std::array<double, 3>, 3> w;
    for (int m = 0; m < 3; ++m) {
      for (int k = 0; k < 3; ++k) {
        const auto at = [&](int i) { return c_[i][k] + t * (c_[i + 4][k] - c_[i][k]); };
        w[m][k] = at(pairs_[m][0]) - at(pairs_[m][1]);
      }
    }
    std::array<double, 3> normal;
    for (int k = 0; k < 3; ++k) {
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      const double n = (w[1][u] - w[0][u]) * (w[2][v] - w[0][v]) - (w[1][v] - w[0][v]) * (w[2][u] - w[0][u]);
      normal[k] = std::isnan(n) ? 0.0 : std::fabs(n);
    }
    std::array<int, 3> axes{0, 1, 2};
    std::sort(axes.begin(), axes.end(), [&](int a, int b) { return normal[a] > normal[b]; });
    return axes;
  }
  // a < b.
  const Poly& cross(int k, int a, int b) {
    const Poly*& p = cross_[k][a][b];
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    if (!p) p = keep(w_[a][u] * w_[b][v] - w_[a][v] * w_[b][u]);
    return *p;
  }
  // a <= b.
  const Poly& dot(int k, int a, int b) {
    const Poly*& p = dot_[k][a][b];
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    if (!p) p = keep(w_[a][u] * w_[b][u] + w_[a][v] * w_[b][v]);
    return *p;
  }
  // The k-th component of the normal (W[1] - W[0]) x (W[2] - W[0]) of W's plane: cross(0, 1) + cross(1, 2) +
  // cross(2, 0) in projection k. Where it is not zero the projection dropping axis k maps the plane through W[0],
  // W[1], W[2] one to one (vertex-face: the face's plane; edge-edge: the plane of da and db, where all four points of
  // W form a parallelogram, so no three of them are collinear).
  const Poly& normal(int k) {
    const Poly*& p = normal_[k];
    if (!p) p = keep(cross(k, 0, 1) + cross(k, 1, 2) - cross(k, 0, 2));
    return *p;
  }

 private:
  Expansion end_cross_value(int end, int k, int a, int b) const {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    return w_at(end, a, u) * w_at(end, b, v) - w_at(end, a, v) * w_at(end, b, u);
  }

  std::array<PolyVector, 3> edges_;  // x[1] - x[0], x[2] - x[0], x[3] - x[0]
  Poly d_;
  bool d_built_ = false;
  std::array<PolyVector, 4> w_;
  int points_ = 0;
  // W[m] at the step's start (end = 0) or end (end = 1), one coordinate, exactly.
  Expansion w_at(int end, int m, int axis) const {
    const auto& pair = pairs_[static_cast<std::size_t>(m)];
    return Expansion::difference(c_[static_cast<std::size_t>(4 * end + pair[0])][static_cast<std::size_t>(axis)],
                                 c_[static_cast<std::size_t>(4 * end + pair[1])][static_cast<std::size_t>(axis)]);
  }

  std::array<std::array<double, 3>, 8> c_;     // the scaled coordinates: start points, then end points
  std::array<std::array<int, 2>, 4> pairs_{};  // W[m] = x[pairs_[m][0]] - x[pairs_[m][1]]
  // The polynomials built so far, at most 3 n^2 + 3 for n points of W (cross and dot products in three projections,
  // three normal components): reserved at once, so one allocation and their addresses stay valid.
  std::vector<Poly> store_;
  const Poly* keep(const Poly& p) {
    if (store_.size() == store_.capacity()) throw ExpansionCapacityExceeded();  // cannot happen; never reallocate
    return &store_.emplace_back(p);
  }
  const Poly* cross_[3][4][4] = {};
  const Poly* dot_[3][4][4] = {};
  const Poly* normal_[3] = {};
};

// Makes the bracketed candidate c the exact rational time of its root when that is cheap to find: the root of a
// linear root_of, or a time in the bracket where two of the points have the same coordinate on one axis and root_of
// vanishes (touching contacts of axis-aligned or sliding geometry). root_of has exactly one root in the bracket, so
// that time is it. Signs at c are then exact homogeneous sums, with no refinement or pseudo-division.
void pin_rational_root(Candidate& c, const System& system) {
  c.pin_tried = true;
  const Poly& p = *c.root_of;
  if (degree(p) == 1) {
    c.rational = true;
    const bool negate = p[1].sign() < 0;
    c.num = negate ? p[0] : -p[0];
    c.den = negate ? -p[1] : p[1];
    return;
  }
  const double lo = c.lo.estimate(), hi = c.hi.estimate();
  const double slack = 1e-9 * (hi - lo) + 1e-15 * (std::fabs(lo) + std::fabs(hi)) + 1e-300;  // estimates only
  Expansion num, den;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      for (int k = 0; k < 3; ++k) {
        // A rounded time far from the bracket skips the exact one (an estimate wrong by cancellation only costs a pin).
        const double rounded = system.alignment_time_estimate(i, j, k);
        if (!(rounded > lo - 1e-6 && rounded < hi + 1e-6)) continue;
        if (!system.alignment_time(i, j, k, num, den)) continue;
        const double r = num.estimate() / den.estimate();
        if (!(r > lo - slack && r < hi + slack)) continue;
        if ((num - den * c.lo).sign() <= 0 || (den * c.hi - num).sign() <= 0) continue;
        if (sign_at_rational(*c.root_of, num, den) != std::optional<int>(0)) continue;
        c.rational = true;
        c.num = num;
        c.den = den;
        return;
      }
    }
  }
}

// The reference's predicate (exact_reference.cpp) at one candidate, with signs computed on first use, and one
// shortcut: every candidate is a time where D = 0, where the points of W span at most a plane through the origin. When
// a triangle of W projects to a non-degenerate triangle with the origin strictly inside (three cross products of one
// strict sign), that projection maps W's plane one to one, so the origin is in the triangle itself: inside, without
// the other projections. The projections go in order of decreasing rounded normal component (the best conditioned
// first), so that this shortcut, or an exclusion, usually comes from the first one. Every candidate is a time where
// D = 0, so W and the origin lie in one plane: when the best projection's normal component N_k (System::normal) is
// not zero there, that projection maps the plane one to one and decides alone, its triangles never degenerate (no dot
// product is needed), and the other projections (often degenerate for the handcrafted contacts) are skipped.
class Predicate {
 public:
  // only_axis >= 0: the projection dropping that axis maps W's plane one to one at the candidate, so it alone decides.
  Predicate(System& system, Candidate& candidate, int only_axis = -1)
      : system_(system), candidate_(candidate), only_axis_(only_axis) {
    for (auto& table : {&cross_, &dot_})
      for (auto& plane : *table)
        for (auto& row : plane) row.fill(kUnknown);
    if (candidate.point && !candidate.rational)
      end_ = candidate.lo.is_double(0.0) ? 0 : (candidate.lo.is_double(1.0) ? 1 : -1);
  }

  // Whether the origin is in conv W at the candidate; nullopt when a sign could not be decided.
  std::optional<bool> holds() {
    bool result = true, strictly = false;
    const double t =
        candidate_.rational ? candidate_.num.estimate() / candidate_.den.estimate() : candidate_.lo.estimate();
    const std::array<int, 3> axes =
        only_axis_ >= 0 ? std::array<int, 3>{only_axis_, only_axis_, only_axis_} : system_.axes_by_normal(t);
    const int axis_count = only_axis_ >= 0 ? 1 : 3;
    for (int i = 0; i < axis_count && result && !strictly; ++i) {
      const int k = axes[static_cast<std::size_t>(i)];
      bool inside = false;
      for (int a = 0; a < system_.points() && !inside; ++a)
        for (int b = a + 1; b < system_.points() && !inside; ++b)
          for (int c = b + 1; c < system_.points() && !inside; ++c)
            inside = triangle_contains_origin(k, a, b, c, strictly);
      result = inside;
      // On a boundary in the best projection: it decides alone when its normal component is not zero (asked only
      // now: an exclusion or a strict inside ends the scan anyway).
      if (i == 0 && result && !strictly && only_axis_ < 0 && normal_sign(k) != 0) break;
    }
    if (failed_) return std::nullopt;
    return result;
  }

 private:
  int sign_of(int& cached, const Poly& p) {
    if (cached == kUnknown) {
      if (!failed_ && !candidate_.pin_tried && !candidate_.point && !candidate_.rational && degree(p) >= 1 &&
          filtered_sign(candidate_, p, degree(p)) == 0)
        pin_rational_root(candidate_, system_);
      const std::optional<int> s = failed_ ? std::optional<int>(0) : sign_at(candidate_, p);
      failed_ = failed_ || !s;
      cached = s.value_or(0);
    }
    return cached;
  }
  // The exact sign of N_k at the candidate, 0 when it is zero or cannot be decided (no failure: only a shortcut).
  int normal_sign(int k) {
    if (end_ >= 0) return system_.end_normal_sign(end_, k);
    const Poly& n = system_.normal(k);
    if (degree(n) < 0) return 0;
    return sign_at(candidate_, n).value_or(0);
  }
  int cross(int k, int a, int b) {
    if (a > b) return -cross(k, b, a);
    int& cached = cross_[k][a][b];
    if (end_ >= 0 && cached == kUnknown) cached = system_.end_cross(end_, k, a, b);
    return cached != kUnknown ? cached : sign_of(cached, system_.cross(k, a, b));
  }
  int dot(int k, int a, int b) {
    if (a > b) std::swap(a, b);
    int& cached = dot_[k][a][b];
    if (end_ >= 0 && cached == kUnknown) cached = system_.end_dot(end_, k, a, b);
    return cached != kUnknown ? cached : sign_of(cached, system_.dot(k, a, b));
  }
  // strictly is set when the origin is strictly inside a non-degenerate projected triangle.
  bool triangle_contains_origin(int k, int a, int b, int c, bool& strictly) {
    const std::array<int, 3> signs{cross(k, a, b), cross(k, b, c), cross(k, c, a)};
    strictly = signs[0] != 0 && signs[0] == signs[1] && signs[1] == signs[2];
    return detail::triangle_contains_origin_by_signs(signs, {a, b, c}, [&](int i, int j) { return dot(k, i, j); });
  }

  static constexpr int kUnknown = 2;
  System& system_;
  Candidate& candidate_;
  int only_axis_ = -1;
  bool failed_ = false;
  int end_ = -1;  // 0 or 1 when the candidate is the step's start or end (signs straight from those positions)
  std::array<std::array<std::array<int, 4>, 4>, 3> cross_{};
  std::array<std::array<std::array<int, 4>, 4>, 3> dot_{};
};

// With D identically zero, an axis k whose projection maps the plane of W (and the origin) one to one at every time
// of the step, or -1: when the Bernstein coefficients of the normal's component N_k (System::normal) on [0, 1] all
// have one strict sign, N_k never vanishes, so the projection is one to one on the plane and no projected triangle of
// W degenerates. Axes are tried by decreasing rounded |N_k| at t = 1/2.
int fixed_projection_axis(System& system) {
  const Expansion zero(0.0), one(1.0);
  for (const int k : system.axes_by_normal(0.5)) {
    const Poly& normal = system.normal(k);
    const int n = degree(normal);
    if (n < 0) continue;
    const BernsteinSigns signs = bernstein_signs(normal, n, zero, one);
    bool one_sign = signs.sign[0] != 0;
    for (std::size_t i = 1; i < static_cast<std::size_t>(signs.count); ++i)
      one_sign = one_sign && signs.sign[i] == signs.sign[0];
    if (one_sign) return k;
  }
  return -1;
}

// D identically zero: W and the origin are coplanar at every time. The set of times where the origin is in conv W is
// closed and its membership changes only at roots of the sign polynomials, so its earliest point (if any) is 0 or
// such a root: the predicate is tested at t = 0, t = 1 and every root of every non-zero sign polynomial.
//
// When one axis projection maps W's plane one to one for the whole step (fixed_projection_axis), that projection alone
// decides, its triangles never degenerate, so only its 2D cross products change the answer: their roots are the only
// candidates besides 0 and 1, and no dot product is needed.
std::optional<exact::ExactAnswer> coplanar_for_whole_step(System& system) {
  const Expansion zero(0.0), one(1.0);
  const int axis = fixed_projection_axis(system);
  // t = 0 first: its signs come straight from the start positions, and a contact there ends the search.
  Candidate start = point_at(zero);
  const std::optional<bool> at_start = Predicate(system, start, axis).holds();
  if (!at_start) return std::nullopt;
  if (*at_start) return exact::ExactAnswer{true, 0.0};
  std::vector<Candidate> candidates{point_at(one)};
  for (int k = 0; k < 3; ++k) {
    if (axis >= 0 && k != axis) continue;
    for (int a = 0; a < system.points(); ++a) {
      for (int b = a; b < system.points(); ++b) {
        if (b > a && !add_roots(system.cross(k, a, b), candidates)) return std::nullopt;
        if (axis < 0 && !add_roots(system.dot(k, a, b), candidates)) return std::nullopt;
      }
    }
  }
  // Roughly earliest first, so that once a contact is found the later brackets are skipped (exactly: a bracket
  // starting after the contact's lower bound cannot lower it).
  std::vector<std::size_t> order(candidates.size());
  std::vector<double> start_estimate(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    order[i] = i;
    const Candidate& c = candidates[i];
    start_estimate[i] = c.rational ? c.num.estimate() / c.den.estimate() : c.lo.estimate();
  }
  // At equal estimates the grid points go first: their signs come cheapest (at t = 1 straight from the end positions).
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (start_estimate[a] != start_estimate[b]) return start_estimate[a] < start_estimate[b];
    return candidates[a].point && !candidates[b].point;
  });
  exact::ExactAnswer answer;
  for (const std::size_t i : order) {
    Candidate& candidate = candidates[i];
    // A candidate not before the contact found cannot lower its time (the time is a double not above the candidate).
    if (answer.hit && not_before(candidate, answer.toi)) continue;
    const std::optional<bool> inside = Predicate(system, candidate, axis).holds();
    if (!inside) return std::nullopt;
    if (*inside) {
      const std::optional<double> toi = lower_bound(candidate);
      if (!toi) return std::nullopt;
      answer.hit = true;
      answer.toi = std::min(answer.toi, *toi);
    }
  }
  return answer;
}

std::optional<exact::ExactAnswer> decide(const CcdQuery& query) {
  const auto coordinates = scaled_coordinates(query);
  if (!coordinates) return std::nullopt;
  System system(query.kind, *coordinates);
  const Poly& d = system.d();
  const int n = degree(d);
  std::vector<Candidate> candidates;
  const Expansion zero(0.0), one(1.0);
  if (n < 0) return coplanar_for_whole_step(system);
  const int s0 = d[0].sign();
  double estimate = 0.0;
  const int s1 = sign_at_time(d, one, estimate);
  if (s0 == 0) candidates.push_back(point_at(zero));
  if (n > 0 && !isolate(d, n, zero, s0, one, s1, 0, candidates)) return std::nullopt;
  if (s1 == 0) candidates.push_back(point_at(one));
  for (Candidate& candidate : candidates) {
    const std::optional<bool> inside = Predicate(system, candidate).holds();
    if (!inside) return std::nullopt;
    if (*inside) {
      const std::optional<double> toi = lower_bound(candidate);
      if (!toi) return std::nullopt;
      return exact::ExactAnswer{true, *toi};
    }
  }
  return exact::ExactAnswer{};
}

// Whether the origin is in conv W at the step's start (end = 0) or end (end = 1): D there exactly zero, then the
// reference's predicate with signs straight from those positions.
std::optional<bool> touches_at(const CcdQuery& query, int end) {
  const auto coordinates = scaled_coordinates(query);
  if (!coordinates) return std::nullopt;
  System system(query.kind, *coordinates);
  if (system.end_d_sign(end) != 0) return false;
  Candidate candidate = point_at(Expansion(end == 0 ? 0.0 : 1.0));
  return Predicate(system, candidate).holds();
}

}  // namespace

std::optional<bool> touches_at_step_end(const CcdQuery& query, int end) {
  try {
    return touches_at(query, end);
  } catch (const ExpansionCapacityExceeded&) {
    return std::nullopt;
  }
}

std::optional<exact::ExactAnswer> expansion_collision(const CcdQuery& query) {
  try {
    return decide(query);
  } catch (const ExpansionCapacityExceeded&) {
    return std::nullopt;  // an exact value too long for the inline expansions: the GMP reference decides
  }
}

}  // namespace clothcd::ccd::detail
