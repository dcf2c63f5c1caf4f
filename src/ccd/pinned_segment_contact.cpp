// The thickness-0 CCD of a pair pinned to a coordinate plane (see pinned_segment_contact.hpp).
//
// On the axis d, the points Z0, Z1 of W have W_d = 0 for the whole step and every other point of W one strict sign
// there: a convex combination with any weight on the others has W_d != 0, so the origin is in conv W(t) exactly when
// it is on the segment Z0(t) Z1(t) of the plane W_d = 0. In that plane's two coordinates, with q = Z0 x Z1 (2D cross
// product) and s = Z0 . Z1, both quadratic in t, the origin is on the segment when q = 0 (collinear) and s <= 0
// (between the ends, or at one). The step is searched left piece first, as in continuous_collision.cpp, with the
// Bernstein coefficients of q and s on a piece from Z at its ends (a product f g of two linear functions has
// f(t0) g(t0), (f(t0) g(t1) + f(t1) g(t0)) / 2 and f(t1) g(t1); the middle one is kept doubled, only signs count):
//   - cleared when q's coefficients have one strict sign (never collinear) or s's are all > 0 (never between);
//   - a hit when q certainly changes sign over the piece and s's coefficients are all < 0: q's only root there is the
//     earliest contact, bracketed by halving to 2^-21 with certain opposite signs of q at the bracket's ends;
//   - split otherwise, within a budget of pieces. What is left (a touch exactly at the segment's end, collinear
//     motion) goes to the exact tiers.
#include "ccd/pinned_segment_contact.hpp"

#include <array>

#include "ccd/interval.hpp"

namespace clothcd::ccd::detail {

namespace {

constexpr double kToiTolerance = 0x1p-21;  // the general fast path's bound on a proven time of impact
constexpr int kPieceBudget = 64;
constexpr int kToiBisections = 40;

// A point of the plane W_d = 0, in its two coordinates.
struct PlanePoint {
  Interval u, v;
};

// The segment's ends Z0, Z1 at one time.
using Segment = std::array<PlanePoint, 2>;

Interval cross(const PlanePoint& a, const PlanePoint& b) { return a.u * b.v - a.v * b.u; }
Interval dot(const PlanePoint& a, const PlanePoint& b) { return a.u * b.u + a.v * b.v; }

// Bernstein coefficients on a piece of the product `product(Z0, Z1)` from the segment at the piece's ends (the middle
// one doubled).
using Coefficients = std::array<Interval, 3>;

template <class Product>
Coefficients bernstein(const Segment& a, const Segment& b, Product product) {
  return {product(a[0], a[1]), product(a[0], b[1]) + product(b[0], a[1]), product(b[0], b[1])};
}

int common_strict_sign(const Coefficients& c) {
  const int s = certain_sign(c[0]);
  return certain_sign(c[1]) == s && certain_sign(c[2]) == s ? s : 0;
}

enum class Outcome { Clear, Hit, Undecided };

struct Search {
  Segment start, change;  // Z(t) = start + t change
  int pieces_left = kPieceBudget;
  double toi = 1.0;

  Segment at(double t) const {  // 0 < t < 1
    Segment z;
    for (std::size_t i = 0; i < 2; ++i) {
      z[i].u = start[i].u + scaled(change[i].u, t);
      z[i].v = start[i].v + scaled(change[i].v, t);
    }
    return z;
  }
};

// The first root of q on [t0, t1], where q has certain opposite signs at the ends (a at t0, b at t1), to within
// kToiTolerance: a left half where q keeps one strict sign is passed over; nullopt when the final bracket's ends do not
// have certain opposite signs of q.
std::optional<double> first_root(const Search& search, double t0, double t1, Segment a, Segment b) {
  for (int i = 0; i < kToiBisections && t1 - t0 > kToiTolerance; ++i) {
    const double mid = 0.5 * (t0 + t1);
    if (!(mid > t0 && mid < t1)) break;
    const Segment m = search.at(mid);
    if (common_strict_sign(bernstein(a, m, cross)) != 0) {
      t0 = mid;
      a = m;
    } else {
      t1 = mid;
      b = m;
    }
  }
  const int s0 = certain_sign(cross(a[0], a[1]));
  if (t1 - t0 > kToiTolerance || s0 == 0 || certain_sign(cross(b[0], b[1])) != -s0) return std::nullopt;
  return t0;
}

Outcome search_piece(Search& search, double t0, double t1, const Segment& a, const Segment& b) {
  const Coefficients q = bernstein(a, b, cross);
  const Coefficients s = bernstein(a, b, dot);
  if (common_strict_sign(q) != 0 || common_strict_sign(s) > 0) return Outcome::Clear;
  const int q0 = certain_sign(q[0]);
  if (q0 != 0 && certain_sign(q[2]) == -q0 && common_strict_sign(s) < 0) {
    // Every earlier piece was cleared, and q's root here is a contact.
    const std::optional<double> toi = first_root(search, t0, t1, a, b);
    if (!toi) return Outcome::Undecided;
    search.toi = *toi;
    return Outcome::Hit;
  }
  const double mid = 0.5 * (t0 + t1);
  if (--search.pieces_left < 0 || !(mid > t0 && mid < t1)) return Outcome::Undecided;
  const Segment m = search.at(mid);
  const Outcome left = search_piece(search, t0, mid, a, m);
  if (left != Outcome::Clear) return left;
  return search_piece(search, mid, t1, m, b);
}

// The sign of the double difference a - b (exact: a rounded difference of two doubles is zero only when they are
// equal, and never changes sign).
int sign_of_difference(double a, double b) { return a > b ? 1 : (a < b ? -1 : 0); }

}  // namespace

std::optional<PinnedAnswer> pinned_segment_contact(const CcdQuery& query) {
  // W[m] = x[first[m]] - x[second[m]].
  const bool vertex_face = query.kind == PairKind::VertexFace;
  const int count = vertex_face ? 3 : 4;
  const std::array<int, 4> first = vertex_face ? std::array<int, 4>{0, 0, 0, 0} : std::array<int, 4>{0, 0, 1, 1};
  const std::array<int, 4> second = vertex_face ? std::array<int, 4>{1, 2, 3, 0} : std::array<int, 4>{2, 3, 2, 3};
  for (int d = 0; d < 3; ++d) {
    std::array<int, 2> pinned{};
    int pinned_count = 0, side = 0;
    bool one_side = true;
    for (int m = 0; m < count && one_side; ++m) {
      const std::size_t i = static_cast<std::size_t>(first[m]), j = static_cast<std::size_t>(second[m]);
      const int at_start = sign_of_difference(query.start[i][d], query.start[j][d]);
      const int at_end = sign_of_difference(query.end[i][d], query.end[j][d]);
      if (at_start == 0 && at_end == 0) {
        if (pinned_count == 2) one_side = false;
        else pinned[static_cast<std::size_t>(pinned_count++)] = m;
        continue;
      }
      // One strict sign at both ends, the same for every point off the plane.
      one_side = at_start != 0 && at_end == at_start && (side == 0 || side == at_start);
      side = at_start;
    }
    if (!one_side || pinned_count != 2 || side == 0) continue;
    const int u = (d + 1) % 3, v = (d + 2) % 3;
    Search search;
    Segment end;
    for (std::size_t k = 0; k < 2; ++k) {
      const std::size_t i = static_cast<std::size_t>(first[pinned[k]]), j = static_cast<std::size_t>(second[pinned[k]]);
      search.start[k] = {exact(query.start[i][u]) - exact(query.start[j][u]),
                         exact(query.start[i][v]) - exact(query.start[j][v])};
      end[k] = {exact(query.end[i][u]) - exact(query.end[j][u]), exact(query.end[i][v]) - exact(query.end[j][v])};
      search.change[k] = {end[k].u - search.start[k].u, end[k].v - search.start[k].v};
    }
    const Outcome outcome = search_piece(search, 0.0, 1.0, search.start, end);
    if (outcome == Outcome::Clear) return PinnedAnswer{};
    if (outcome == Outcome::Hit) return PinnedAnswer{true, search.toi};
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace clothcd::ccd::detail
