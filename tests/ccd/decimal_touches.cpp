// The decimal touch queries (decimal_touches.hpp). A point computed in doubles on a face or an edge is only within a
// rounding error of it, so most constructions are near touches that the exact reference labels (about half collide,
// within an ulp of the contact); the exact ones come from equal doubles (a vertex on a corner, a shared end point) or
// from axis-aligned pieces (an edge along x, a motion along x through a corner, a common plane z = c).
#include "ccd/decimal_touches.hpp"

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace clothcd::test {

namespace {

using Eigen::Vector3d;

constexpr int kDigits = 5;  // grid steps per feature size: 10^-kDigits
constexpr int kSmallestExponent = -3;
constexpr int kLargestExponent = 3;
constexpr double kOffsets[] = {0.0, 2.7, -1300.0};  // in feature sizes
constexpr int kPerGrid = 90;                        // constructions of each kind per grid

// Points on the grid 10^(exponent - kDigits) Z^3 around an offset: every coordinate is an integer divided by a power of
// ten (correctly rounded, as a decimal literal would be).
class DecimalGrid {
 public:
  DecimalGrid(int exponent, double offset, std::uint64_t seed)
      : exponent_(exponent),
        divisor_(std::pow(10.0, kDigits - exponent)),
        center_(std::llround(offset * std::pow(10.0, kDigits))),
        random_(seed) {}

  int exponent() const { return exponent_; }
  // The feature size 10^exponent.
  double scale() const { return value(std::llround(std::pow(10.0, kDigits))); }
  double value(long long units) const { return static_cast<double>(units) / divisor_; }
  double snap(double x) const { return value(std::llround(x * divisor_)); }
  Vector3d snap(const Vector3d& p) const { return {snap(p.x()), snap(p.y()), snap(p.z())}; }
  // A grid point within `spread` feature sizes of the offset in each coordinate.
  Vector3d point(double spread = 1.0) {
    const long long reach = std::llround(spread * std::pow(10.0, kDigits));
    std::uniform_int_distribution<long long> step(-reach, reach);
    return {value(center_ + step(random_)), value(center_ + step(random_)), value(center_ + step(random_))};
  }
  // A grid displacement of up to `spread` feature sizes.
  Vector3d displacement(double spread) { return point(spread) - point(0.0); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  bool coin() { return pick(2) == 1; }
  Vector3d unit() {
    Vector3d v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return v.norm() > 1e-3 ? v.normalized() : Vector3d::UnitX();
  }

 private:
  int exponent_;
  double divisor_;
  long long center_;
  std::mt19937_64 random_;
};

ccd::CcdQuery make(PairKind kind, const std::array<Vector3d, 4>& start, const std::array<Vector3d, 4>& end) {
  ccd::CcdQuery q;
  q.kind = kind;
  q.start = start;
  q.end = end;
  return q;
}

Vector3d unit_normal(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  return n.norm() > 0.0 ? n.normalized() : Vector3d::UnitZ();
}

// A triangle at t = 0 from its position at t = 1: the same (a static face) or moved by a small grid displacement.
std::array<Vector3d, 3> moved_back(DecimalGrid& grid, const std::array<Vector3d, 3>& end) {
  if (grid.coin()) return end;
  std::array<Vector3d, 3> start;
  for (int k = 0; k < 3; ++k) start[k] = grid.snap(end[k] + grid.displacement(0.15));
  return start;
}

// Vertex-face, the vertex arriving on the face at t = 1 from one side. Mode 0: a point inside (convex combination,
// rounded); 1: a point on an edge (rounded); 2: a corner (equal doubles, exact); 3: a grid point on an edge along x
// (exact).
ccd::CcdQuery vertex_face_at_end(DecimalGrid& grid, int mode, bool& exact) {
  std::array<Vector3d, 3> face{grid.point(), grid.point(), grid.point()};
  Vector3d contact;
  exact = mode >= 2;
  if (mode == 0) {
    const double a = grid.uniform(0.02, 0.9), b = grid.uniform(0.02, 1.0 - a);
    contact = (1.0 - a - b) * face[0] + a * face[1] + b * face[2];
  } else if (mode == 1) {
    const int i = grid.pick(3);
    contact = face[i] + grid.uniform(0.02, 0.98) * (face[(i + 1) % 3] - face[i]);
  } else if (mode == 2) {
    contact = face[grid.pick(3)];
  } else {
    face[1].y() = face[0].y();
    face[1].z() = face[0].z();
    contact = face[0];
    contact.x() = grid.snap(face[0].x() + grid.uniform(0.05, 0.95) * (face[1].x() - face[0].x()));
  }
  const Vector3d n = unit_normal(face[0], face[1], face[2]);
  const double side = grid.coin() ? 1.0 : -1.0;
  const Vector3d from =
      grid.snap(contact + grid.scale() * (side * grid.uniform(0.1, 1.0) * n + 0.3 * grid.uniform(-1, 1) * grid.unit()));
  const std::array<Vector3d, 3> face0 = moved_back(grid, face);
  return make(PairKind::VertexFace, {from, face0[0], face0[1], face0[2]}, {contact, face[0], face[1], face[2]});
}

// Vertex-face, the vertex arriving at t = 1 near the middle of a wide face whose plane passes through the grid's
// center: corners center + 10^exponent * (integer vector), the third minus the sum of the other two (exact for
// features of size >= 1 at the origin, so the face normal is computed exactly there), and a vertex with decimal x
// and y whose z comes from the plane equation, rounded: it lands within a rounding error of its own (small)
// coordinates from the plane, while its differences to the far corners round by much more. These are the touches
// the filters' rounding terms exist for.
ccd::CcdQuery vertex_onto_wide_face(DecimalGrid& grid) {
  const Vector3d center = grid.point(0.0);
  std::array<Vector3d, 3> steps;
  Vector3d n = Vector3d::Zero();
  while (n == Vector3d::Zero()) {  // until the corners are not collinear
    for (int k = 0; k < 2; ++k) {
      for (int c = 0; c < 3; ++c) steps[k][c] = grid.pick(199) - 99;
    }
    steps[2] = -(steps[0] + steps[1]);
    n = (steps[1] - steps[0]).cross(steps[2] - steps[0]);
  }
  std::array<Vector3d, 3> face;
  for (int k = 0; k < 3; ++k) face[k] = center + grid.scale() * steps[k];
  // Decimal x and y within 0.05 feature sizes of the center, z on the plane n . (p - center) = 0 (in the largest
  // component of n, so the face is not seen edge-on).
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  Vector3d offset;
  for (int c = 0; c < 3; ++c) offset[c] = grid.value(grid.pick(10001) - 5000);
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  offset[axis] = -(n[u] * offset[u] + n[v] * offset[v]) / n[axis];
  const Vector3d contact = center + offset;
  const Vector3d normal = n.normalized();
  const Vector3d from = grid.snap(contact + grid.scale() * ((grid.coin() ? 1.0 : -1.0) * grid.uniform(0.1, 1.0) * normal +
                                                            0.3 * grid.uniform(-1, 1) * grid.unit()));
  return make(PairKind::VertexFace, {from, face[0], face[1], face[2]}, {contact, face[0], face[1], face[2]});
}

// A point near `near` whose coordinates sum exactly (in rationals) to `sum`: x and y on the grid, z = sum - x - y
// rounded, drawn again until that rounding was exact (at most 200 times; then a point within a rounding error of
// the plane, which the reference labels like any other).
Vector3d on_diagonal_plane(DecimalGrid& grid, double sum, const Vector3d& near, double spread) {
  Vector3d p;
  for (int attempt = 0; attempt < 200; ++attempt) {
    p = grid.snap(near + grid.displacement(spread));
    p.z() = (sum - p.x()) - p.y();
    if (mpq_class(p.x()) + mpq_class(p.y()) + mpq_class(p.z()) == mpq_class(sum)) break;
  }
  return p;
}

// Vertex-face on the plane x + y + z = s (exactly, in rationals): the face's corners and the vertex at t = 1 all lie
// on it, the vertex near the face's centroid, arriving along the plane's normal (1, 1, 1), a direction of eq. (10).
// Their projections x + y + z are equal in exact arithmetic but rounded twice in the filters (in the block filter
// without a difference first): only the rounding term keeps the fixed direction from separating them.
ccd::CcdQuery vertex_onto_diagonal_face(DecimalGrid& grid) {
  const Vector3d center = grid.point();
  const double sum = grid.snap(center.sum());
  std::array<Vector3d, 3> face;
  for (Vector3d& corner : face) corner = on_diagonal_plane(grid, sum, center, 1.0);
  const Vector3d contact = on_diagonal_plane(grid, sum, (face[0] + face[1] + face[2]) / 3.0, 0.02);
  const Vector3d normal = Vector3d::Ones().normalized() * (grid.coin() ? 1.0 : -1.0);
  const Vector3d from =
      grid.snap(contact + grid.scale() * (grid.uniform(0.1, 1.0) * normal + 0.3 * grid.uniform(-1, 1) * grid.unit()));
  return make(PairKind::VertexFace, {from, face[0], face[1], face[2]}, {contact, face[0], face[1], face[2]});
}

// Edge-edge, edge a arriving on edge b at t = 1 from one side. Mode 0: a through a point of b (rounded); 1: an end of
// a on b (rounded); 2: a shared end point (equal doubles, exact); 3: a along y crossing b along x in a plane z = c
// (exact).
ccd::CcdQuery edge_edge_at_end(DecimalGrid& grid, int mode, bool& exact) {
  std::array<Vector3d, 4> end{grid.point(), grid.point(), grid.point(), grid.point()};
  exact = mode >= 2;
  const Vector3d on_b = end[2] + grid.uniform(0.02, 0.98) * (end[3] - end[2]);
  if (mode == 0) {
    end[0] = grid.snap(on_b + grid.scale() * grid.uniform(0.2, 1.0) * grid.unit());
    end[1] = on_b + grid.uniform(0.2, 2.0) * (on_b - end[0]);
  } else if (mode == 1) {
    end[0] = on_b;
  } else if (mode == 2) {
    end[grid.pick(2)] = end[2 + grid.pick(2)];
  } else {
    end[3].y() = end[2].y();
    end[3].z() = end[2].z();
    const double x = grid.snap(end[2].x() + grid.uniform(0.05, 0.95) * (end[3].x() - end[2].x()));
    const double reach = grid.scale();
    end[0] = Vector3d(x, grid.snap(end[2].y() - grid.uniform(0.05, 1.0) * reach), end[2].z());
    end[1] = Vector3d(x, grid.snap(end[2].y() + grid.uniform(0.05, 1.0) * reach), end[2].z());
  }
  const Vector3d n = unit_normal(end[0], end[1], end[0] + (end[3] - end[2]));
  const Vector3d away = grid.snap(grid.scale() * ((grid.coin() ? 1.0 : -1.0) * grid.uniform(0.1, 1.0) * n +
                                                  0.3 * grid.uniform(-1, 1) * grid.unit()));
  std::array<Vector3d, 4> start = end;
  start[0] = end[0] + away;
  start[1] = end[1] + away;
  if (grid.coin()) {
    start[2] = grid.snap(end[2] + grid.displacement(0.15));
    start[3] = grid.snap(end[3] + grid.displacement(0.15));
  }
  return make(PairKind::EdgeEdge, start, end);
}

// The same motion run backwards: contact at t = 0.
ccd::CcdQuery reversed(const ccd::CcdQuery& q) { return make(q.kind, q.end, q.start); }

// An AtEnd motion continued past its contact: the end positions start + f (end - start), rounded.
ccd::CcdQuery prolonged(DecimalGrid& grid, const ccd::CcdQuery& q) {
  const double f = grid.uniform(1.1, 4.0);
  ccd::CcdQuery out = q;
  for (int i = 0; i < 4; ++i) out.end[i] = q.start[i] + f * (q.end[i] - q.start[i]);
  return out;
}

// A point sliding along x exactly through a corner of the other primitive at an interior time (vertex-face: the
// vertex through a corner of a static face; edge-edge: an end of edge a through an end of edge b, edge a moving
// along x).
ccd::CcdQuery sliding_through_corner(DecimalGrid& grid, PairKind kind) {
  const double before = grid.snap(grid.scale() * grid.uniform(0.05, 1.0));
  const double after = grid.snap(grid.scale() * grid.uniform(0.05, 1.0));
  if (kind == PairKind::VertexFace) {
    const std::array<Vector3d, 3> face{grid.point(), grid.point(), grid.point()};
    const Vector3d corner = face[grid.pick(3)];
    Vector3d from = corner, to = corner;
    from.x() -= before;
    to.x() += after;
    return make(kind, {from, face[0], face[1], face[2]}, {to, face[0], face[1], face[2]});
  }
  std::array<Vector3d, 4> start{Vector3d::Zero(), grid.point(), grid.point(), grid.point()};
  start[0] = start[2];
  start[0].x() -= before;
  std::array<Vector3d, 4> end = start;
  for (int i = 0; i < 2; ++i) end[i].x() += before + after;
  return make(kind, start, end);
}

// All eight points on the plane z = c: a vertex or an edge moving in the plane across or along the other primitive.
ccd::CcdQuery coplanar(DecimalGrid& grid, PairKind kind) {
  const double z = grid.point().z();
  std::array<Vector3d, 4> start, end;
  for (int i = 0; i < 4; ++i) {
    start[i] = grid.point(0.5);
    end[i] = i < (kind == PairKind::VertexFace ? 1 : 2) || grid.coin() ? grid.point(0.5) : start[i];
    start[i].z() = end[i].z() = z;
  }
  return make(kind, start, end);
}

// One coordinate of one point moved by one to three ulps either way.
ccd::CcdQuery nudged(DecimalGrid& grid, ccd::CcdQuery q) {
  double& x = (grid.coin() ? q.start : q.end)[grid.pick(4)][grid.pick(3)];
  const double towards = grid.coin() ? HUGE_VAL : -HUGE_VAL;
  for (int k = 1 + grid.pick(3); k > 0; --k) x = std::nextafter(x, towards);
  return q;
}

// Vertex-face, the vertex ending at distance about `thickness` above a point inside the face.
ccd::CcdQuery vertex_near_face(DecimalGrid& grid, double thickness) {
  const std::array<Vector3d, 3> face{grid.point(), grid.point(), grid.point()};
  const double a = grid.uniform(0.05, 0.9), b = grid.uniform(0.05, 0.95 - a);
  const Vector3d foot = (1.0 - a - b) * face[0] + a * face[1] + b * face[2];
  const Vector3d n = unit_normal(face[0], face[1], face[2]) * (grid.coin() ? 1.0 : -1.0);
  const Vector3d end = foot + thickness * n;
  const Vector3d from = grid.snap(end + grid.scale() * (grid.uniform(0.1, 1.0) * n + 0.3 * grid.uniform(-1, 1) * grid.unit()));
  return make(PairKind::VertexFace, {from, face[0], face[1], face[2]}, {end, face[0], face[1], face[2]});
}

using Rational3 = std::array<mpq_class, 3>;

Rational3 rational(const Vector3d& p) { return {mpq_class(p.x()), mpq_class(p.y()), mpq_class(p.z())}; }
Rational3 minus(const Rational3& a, const Rational3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Rational3 cross(const Rational3& a, const Rational3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot(const Rational3& a, const Rational3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Exactly: the vertex's distance to the face's plane at t = 1 is <= thickness and its foot lies inside the face (so
// it is the point-triangle distance).
bool ends_within(const ccd::CcdQuery& q, double thickness) {
  const Rational3 p = rational(q.end[0]), a = rational(q.end[1]), b = rational(q.end[2]), c = rational(q.end[3]);
  const Rational3 n = cross(minus(b, a), minus(c, a));
  const mpq_class nn = dot(n, n);
  if (sgn(nn) == 0) return false;
  for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}}) {
    if (sgn(dot(cross(minus(*to, *from), minus(p, *from)), n)) < 0) return false;
  }
  const mpq_class height = dot(n, minus(p, a));
  const mpq_class h(thickness);
  return height * height <= h * h * nn;
}

std::uint64_t grid_seed(int exponent, int offset_index) {
  return 0x5eed0000u + static_cast<std::uint64_t>((exponent + 10) * 8 + offset_index);
}

}  // namespace

std::vector<double> touch_thicknesses(int exponent) {
  const double scale = std::pow(10.0, exponent);
  return {1e-9 * scale, 1e-4 * scale, 0.03 * scale};
}

const std::vector<LabelledTouch>& decimal_touches() {
  static const std::vector<LabelledTouch> touches = [] {
    std::vector<LabelledTouch> out;
    auto add = [&](const ccd::CcdQuery& q, TouchFamily family, int exponent) {
      out.push_back({q, ccd::exact_collision_reference(q), family, exponent});
    };
    for (int exponent = kSmallestExponent; exponent <= kLargestExponent; ++exponent) {
      for (int o = 0; o < static_cast<int>(std::size(kOffsets)); ++o) {
        DecimalGrid grid(exponent, kOffsets[o], grid_seed(exponent, o));
        for (int i = 0; i < kPerGrid; ++i) {
          for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
            bool exact = false;
            const ccd::CcdQuery at_end = kind == PairKind::VertexFace ? vertex_face_at_end(grid, i % 4, exact)
                                                                      : edge_edge_at_end(grid, i % 4, exact);
            add(at_end, TouchFamily::AtEnd, exponent);
            add(reversed(at_end), TouchFamily::AtStart, exponent);
            if (i % 2 == 0) add(prolonged(grid, at_end), TouchFamily::Interior, exponent);
            if (i % 2 == 1) {
              const ccd::CcdQuery sliding = sliding_through_corner(grid, kind);
              add(sliding, TouchFamily::Interior, exponent);
              add(nudged(grid, sliding), TouchFamily::Nudged, exponent);
            }
            if (exact) add(nudged(grid, at_end), TouchFamily::Nudged, exponent);
            if (kind == PairKind::VertexFace) {
              for (const ccd::CcdQuery& on_plane : {vertex_onto_wide_face(grid), vertex_onto_diagonal_face(grid)}) {
                add(on_plane, TouchFamily::AtEnd, exponent);
                add(reversed(on_plane), TouchFamily::AtStart, exponent);
              }
            }
            if (i % 15 == 0) add(coplanar(grid, kind), TouchFamily::Coplanar, exponent);
          }
        }
      }
    }
    return out;
  }();
  return touches;
}

const std::vector<ThickTouch>& decimal_thick_touches() {
  static const std::vector<ThickTouch> touches = [] {
    std::vector<ThickTouch> out;
    for (int exponent = kSmallestExponent; exponent <= kLargestExponent; ++exponent) {
      for (int o = 0; o < static_cast<int>(std::size(kOffsets)); ++o) {
        DecimalGrid grid(exponent, kOffsets[o], grid_seed(exponent, o) + 1000);
        for (int i = 0; i < kPerGrid; ++i) {
          const std::vector<double> thicknesses = touch_thicknesses(exponent);
          const double thickness = thicknesses[static_cast<std::size_t>(i) % thicknesses.size()];
          const ccd::CcdQuery q = vertex_near_face(grid, thickness);
          if (ends_within(q, thickness)) out.push_back({q, thickness, exponent});
        }
      }
    }
    return out;
  }();
  return touches;
}

}  // namespace clothcd::test
