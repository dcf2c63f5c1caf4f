// The slow, exact CCD reference (GMP rationals), thickness 0.
//
// Both pair kinds reduce to one question: is the origin in conv W(t) for some t in [0, 1], where W(t) is a set of
// points linear in t: W = {v - f_i} (3 points, vertex minus triangle corners) for vertex-face, and W = {a_i - b_j}
// (4 points, the Minkowski difference of the two segments) for edge-edge. The origin can only be in conv W(t) when
// W(t) and the origin are coplanar, i.e. when D(t) = det(x1 - x0, x2 - x0, x3 - x0) = 0 (the coplanarity cubic of
// section 2.2). For points coplanar with the origin, 0 in conv W holds iff 0 is in the convex hull of every axis
// projection of W (a projection along an axis not parallel to the plane is injective on it), and in 2D iff some
// (possibly degenerate) triangle of W contains 0 (Caratheodory), which is a sign condition on 2D cross and dot
// products. All these are polynomials in t; their signs are evaluated exactly at the real roots of D (or, when D is
// identically zero, at all roots of the other polynomials and at sample points between them, where every sign and
// hence the answer is constant).
#include "ccd/exact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "ccd/exact_polynomial.hpp"
#include "ccd/projected_triangle.hpp"

namespace clothcd::ccd::exact {

namespace {

using Vector = std::array<Polynomial, 3>;

Vector subtract(const Vector& a, const Vector& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Polynomial determinant(const Vector& a, const Vector& b, const Vector& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The polynomials whose signs decide the question, with index tables for the predicate.
struct SignSystem {
  std::vector<Polynomial> polys;                                      // polys[0] = D
  mutable std::vector<std::unique_ptr<PreparedPolynomial>> prepared;  // filled on first use, it costs GMP divisions

  const PreparedPolynomial& prepared_poly(int i) const {
    if (!prepared[i]) prepared[i] = std::make_unique<PreparedPolynomial>(prepare(polys[i]));
    return *prepared[i];
  }
  int points = 0;
  int cross[3][4][4] = {};  // cross[k][a][b]: 2D cross product of W[a], W[b] in the projection dropping axis k
  int dot[3][4][4] = {};    // dot[k][a][b]: 2D dot product in that projection
};

SignSystem build_system(PairKind kind, const RationalPoints& points) {
  // Scaling all coordinates by their positive common denominator changes no sign and makes every polynomial integer.
  mpz_class common_denominator = 1;
  for (const auto& point : points)
    for (const mpq_class& c : point)
      mpz_lcm(common_denominator.get_mpz_t(), common_denominator.get_mpz_t(), c.get_den_mpz_t());
  const mpq_class scale(common_denominator);
  std::array<Vector, 4> x;
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) x[i][d] = linear(points[i][d] * scale, (points[i + 4][d] - points[i][d]) * scale);
  SignSystem system;
  system.polys.push_back(determinant(subtract(x[1], x[0]), subtract(x[2], x[0]), subtract(x[3], x[0])));
  std::vector<Vector> w;
  if (kind == PairKind::VertexFace) {
    for (int i = 1; i < 4; ++i) w.push_back(subtract(x[0], x[i]));
  } else {
    for (int i = 0; i < 2; ++i)
      for (int j = 2; j < 4; ++j) w.push_back(subtract(x[i], x[j]));
  }
  system.points = static_cast<int>(w.size());
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3;
    const int v = (k + 2) % 3;
    for (int a = 0; a < system.points; ++a) {
      for (int b = a; b < system.points; ++b) {
        system.cross[k][a][b] = static_cast<int>(system.polys.size());
        system.polys.push_back(w[a][u] * w[b][v] - w[a][v] * w[b][u]);
        system.dot[k][a][b] = system.dot[k][b][a] = static_cast<int>(system.polys.size());
        system.polys.push_back(w[a][u] * w[b][u] + w[a][v] * w[b][v]);
      }
    }
  }
  system.prepared.resize(system.polys.size());
  return system;
}

// Exact signs of the system's polynomials at one point, computed on first use.
class Signs {
 public:
  Signs(const SignSystem& system, AlgebraicPoint& point)
      : system_(system), point_(point), cache_(system.polys.size(), kUnknown) {}
  int operator[](int i) {
    if (cache_[i] == kUnknown) cache_[i] = sign_at(point_, system_.prepared_poly(i));
    return cache_[i];
  }

 private:
  static constexpr int kUnknown = 2;
  const SignSystem& system_;
  AlgebraicPoint& point_;
  std::vector<int> cache_;
};

// Sign of the 2D cross product W[a] x W[b] (antisymmetric; the table stores a <= b).
int cross_sign(const SignSystem& system, Signs& signs, int k, int a, int b) {
  return a <= b ? signs[system.cross[k][a][b]] : -signs[system.cross[k][b][a]];
}

bool triangle_contains_origin(const SignSystem& system, Signs& signs, int k, int a, int b, int c) {
  return detail::triangle_contains_origin_by_signs(
      {cross_sign(system, signs, k, a, b), cross_sign(system, signs, k, b, c), cross_sign(system, signs, k, c, a)},
      {a, b, c}, [&](int i, int j) { return signs[system.dot[k][i][j]]; });
}

bool predicate(const SignSystem& system, Signs& signs) {
  if (signs[0] != 0) return false;
  for (int k = 0; k < 3; ++k) {
    bool inside = false;
    for (int a = 0; a < system.points && !inside; ++a)
      for (int b = a + 1; b < system.points && !inside; ++b)
        for (int c = b + 1; c < system.points && !inside; ++c)
          inside = triangle_contains_origin(system, signs, k, a, b, c);
    if (!inside) return false;
  }
  return true;
}

double lower_bound_as_double(const AlgebraicPoint& point) {
  // mpq_get_d truncates toward zero, which rounds down for the non-negative times used here.
  return point.is_rational ? point.value.get_d() : point.lo.get_d();
}

// The candidate times (roots of D, or with D identically zero the roots of the other polynomials and samples between
// them) at which the primitives touch; their earliest is the earliest contact.
std::vector<AlgebraicPoint> contact_points(PairKind kind, const RationalPoints& points) {
  const SignSystem system = build_system(kind, points);
  std::vector<AlgebraicPoint> candidates;
  if (!is_zero(system.polys[0])) {
    candidates = roots_in_unit_interval(system.polys[0]);
  } else {
    // Every sign is constant between consecutive roots of the non-zero polynomials: test those roots and a rational
    // sample inside every open piece between them. Once no polynomial has a root in [lo, hi] but the point itself, lo
    // and hi lie in the pieces next to an irrational root; the midpoints of consecutive samples cover the rest.
    std::vector<PreparedPolynomial> all_prepared;
    for (std::size_t i = 0; i < system.polys.size(); ++i)
      all_prepared.push_back(system.prepared_poly(static_cast<int>(i)));
    std::vector<mpq_class> samples{mpq_class(0), mpq_class(1)};
    for (std::size_t i = 1; i < system.polys.size(); ++i) {
      if (degree(system.polys[i]) < 1) continue;
      for (AlgebraicPoint& root : roots_in_unit_interval(system.polys[i])) {
        isolate_from(root, all_prepared);
        if (root.is_rational) {
          samples.push_back(root.value);
        } else {
          samples.push_back(root.lo);
          samples.push_back(root.hi);
          candidates.push_back(std::move(root));
        }
      }
    }
    std::sort(samples.begin(), samples.end());
    samples.erase(std::unique(samples.begin(), samples.end()), samples.end());
    const std::size_t sorted_count = samples.size();
    for (std::size_t i = 0; i + 1 < sorted_count; ++i) samples.push_back((samples[i] + samples[i + 1]) / 2);
    for (const mpq_class& t : samples) candidates.push_back(AlgebraicPoint{true, t, {}, t, t});
  }
  std::vector<AlgebraicPoint> contacts;
  for (AlgebraicPoint& point : candidates) {
    Signs signs(system, point);
    if (predicate(system, signs)) contacts.push_back(std::move(point));
  }
  return contacts;
}

// The smallest double >= the non-negative rational x.
double rounded_up(const mpq_class& x) {
  const double d = x.get_d();
  return mpq_class(d) < x ? std::nextafter(d, 2.0) : d;
}

}  // namespace

ExactAnswer exact_collision(PairKind kind, const RationalPoints& points) {
  ExactAnswer answer;
  for (const AlgebraicPoint& point : contact_points(kind, points)) {
    answer.hit = true;
    answer.toi = std::min(answer.toi, lower_bound_as_double(point));
  }
  return answer;
}

ContactTimeBounds exact_contact_time(PairKind kind, const RationalPoints& points) {
  const mpq_class width(1, mpz_class(1) << 40);
  ContactTimeBounds bounds;
  for (AlgebraicPoint& point : contact_points(kind, points)) {
    narrow(point, width);
    bounds.hit = true;
    bounds.lo = std::min(bounds.lo, lower_bound_as_double(point));
    bounds.hi = std::min(bounds.hi, rounded_up(point.is_rational ? point.value : point.hi));
  }
  return bounds;
}

}  // namespace clothcd::ccd::exact
