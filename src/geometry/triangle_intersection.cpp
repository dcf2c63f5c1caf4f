// The triangle intersection test on exact orientation signs. Not coplanar, the two triangles meet the line L of their
// planes in two segments, and intersect iff those overlap: without shared corners two orient3d compare their ends
// (Devillers and Guigue 2002); with a shared vertex, an end of both, the signs of the corners against the planes
// tell the directions in which they leave it; with a shared edge they meet beyond it only when coplanar.
// For the crossing point, and for coplanar pairs, the rest rests on one fact: the common set C of two closed
// triangles is convex, and its extreme points lie on edges (of one triangle, inside the other), so C has a point
// outside the hull S of the shared corners iff some edge of one triangle meets the other outside S. The tests below
// enumerate just enough of those edge points:
//   - not coplanar: each edge crossing the other's plane (endpoints on both sides, or one on it) meets the other
//     triangle iff its line passes it on one side of all three edges (orient3d of the two edges); an edge lying in
//     the other's plane needs no test, as C's extreme points on it are found on the adjacent crossing edges. With a
//     shared vertex only the edges opposite it can meet the other beyond it (the farthest common point along an edge
//     from v is a corner of one, or on an opposite edge).
//   - coplanar (orient2d on a coordinate plane along which the triangles project non-degenerately, so the projection
//     keeps every incidence): the corners (not shared) inside the other triangle, and the crossings of two edges that
//     contain no common shared corner (a crossing of edges through one shared corner is that corner). Faces sharing
//     an edge and folded onto each other always overlap.
#include "geometry/triangle_intersection.hpp"

#include <algorithm>
#include <limits>

#include "geometry/exact_triangle_intersection.hpp"
#include "geometry/orientation_filter.hpp"

namespace clothcd::geometry {

namespace {

using filter::kUndecided;

// The shared corners as partner tables.
struct Sharing {
  int count = 0;
  int b_of_a[3] = {-1, -1, -1};
  int a_of_b[3] = {-1, -1, -1};
};

Sharing sharing_of(const SharedCorners& shared) {
  Sharing sharing;
  sharing.count = shared.count;
  for (int k = 0; k < shared.count; ++k) {
    sharing.b_of_a[shared.pairs[k][0]] = shared.pairs[k][1];
    sharing.a_of_b[shared.pairs[k][1]] = shared.pairs[k][0];
  }
  return sharing;
}

double clamp_unit(double t) {
  return t > 0.0 ? (t < 1.0 ? t : 1.0) : 0.0;
}

// (w1, w2) from three determinants proportional to the corners' barycentric weights, whose exact signs agree (or are
// zero): a rounded value whose sign is not the exact one counts as zero.
std::array<double, 2> normalized_weights(const Orientation& o0, const Orientation& o1, const Orientation& o2) {
  const auto magnitude = [](const Orientation& o) { return o.value * o.sign > 0.0 ? std::abs(o.value) : 0.0; };
  double w0 = magnitude(o0), w1 = magnitude(o1), w2 = magnitude(o2);
  double sum = w0 + w1 + w2;
  if (!(sum > 0.0) || !(sum <= std::numeric_limits<double>::max())) {  // only rounding left: the signs alone
    w0 = o0.sign != 0, w1 = o1.sign != 0, w2 = o2.sign != 0;
    sum = w0 + w1 + w2;
  }
  const double first = w1 / sum;
  return {first, std::min(w2 / sum, 1.0 - first)};
}

// The parameter of the zero of a function that is `from` at s = 0 and `to` at s = 1 (exact signs given).
double zero_parameter(const Orientation& from, const Orientation& to) {
  if (from.sign == 0) return 0.0;
  if (to.sign == 0) return 1.0;
  // Rounded values whose signs are not the exact ones: the zero is within rounding of both ends.
  if (from.value * from.sign <= 0.0 || to.value * to.sign <= 0.0) return from.value * from.sign <= 0.0 ? 0.0 : 1.0;
  return clamp_unit(from.value / (from.value - to.value));
}

template <bool kCrossing>
class PairTest {
 public:
  PairTest(const Triangle& a, const Triangle& b, const SharedCorners& shared)
      : a_(a), b_(b), shared_(shared), sharing_(sharing_of(shared)) {}

  TriangleContact run() {
    if (sharing_.count == 3) return coplanar_miss();
    const filter::PlaneFilter plane_a(a_[0], a_[1], a_[2]);
    if (sides(plane_a, a_, b_, sharing_.a_of_b, b_sides_)) return {};
    if (all_zero(b_sides_)) return coplanar(plane_a);
    const filter::PlaneFilter plane_b(b_[0], b_[1], b_[2]);
    if (sides(plane_b, b_, a_, sharing_.b_of_a, a_sides_)) return {};
    // Some corner of b is off a's plane, so a is not degenerate; b is unless a lies in its plane.
    if (all_zero(a_sides_)) return exact_intersect_triangles(a_, b_, shared_);
    return crossing();
  }

 private:
  // Signs of `points` against the plane of `face` (0 for a corner shared with it); true when the unshared corners
  // are all strictly on one side, so that the other triangle meets the plane only in the hull of shared corners.
  static bool sides(const filter::PlaneFilter& plane, const Triangle& face, const Triangle& points,
                    const int (&partner)[3], Orientation (&out)[3]) {
    bool positive = true, negative = true;
    for (int j = 0; j < 3; ++j) {
      if (partner[j] >= 0) {
        out[j] = {};
        continue;
      }
      out[j] = plane.side(points[j]);
      if (out[j].sign == kUndecided) out[j].sign = exact_orient3d(face[0], face[1], face[2], points[j]);
      positive = positive && out[j].sign > 0;
      negative = negative && out[j].sign < 0;
    }
    return positive || negative;
  }

  static bool all_zero(const Orientation (&s)[3]) { return s[0].sign == 0 && s[1].sign == 0 && s[2].sign == 0; }

  static TriangleContact coplanar_miss() {
    TriangleContact contact;
    contact.coplanar = true;
    return contact;
  }

  // Edge i of a and edge j of b contain a common shared corner.
  bool edges_share_corner(int i, int j) const {
    for (int c : {i, (i + 1) % 3}) {
      const int partner = sharing_.b_of_a[c];
      if (partner == j || partner == (j + 1) % 3) return true;
    }
    return false;
  }

  // orient3d(a_i, a_i+1, b_j, b_j+1), which equals orient3d(b_j, b_j+1, a_i, a_i+1).
  const Orientation& edge_edge(int i, int j) {
    if (!edge_edge_known_[i][j]) {
      edge_edge_known_[i][j] = true;
      Orientation& o = edge_edge_[i][j];
      if (edges_share_corner(i, j)) {
        o = {};
      } else {
        const Eigen::Vector3d &p = a_[i], &q = a_[(i + 1) % 3], &r = b_[j], &s = b_[(j + 1) % 3];
        o = filter::PlaneFilter(p, q, r).side(s);
        if (o.sign == kUndecided) o.sign = exact_orient3d(p, q, r, s);
      }
    }
    return edge_edge_[i][j];
  }

  // Not coplanar, both triangles non-degenerate, no shared corner or one (faces sharing an edge were rejected by the
  // plane sides): decided on the line L of the two planes, which each triangle meets in a segment (its common points
  // with the other's plane); the crossing point, when wanted, from the edges.
  TriangleContact crossing() {
    TriangleContact contact;
    contact.intersect = sharing_.count == 0 ? segments_overlap() : beyond_shared_vertex();
    if constexpr (kCrossing) {
      if (contact.intersect) find_crossing(contact);
    }
    return contact;
  }

  // The corner of a triangle alone on its side of the other's plane (the others on the opposite side or in the
  // plane), and that side; a corner in the plane counts as alone, on the side opposite the others, when they are
  // strictly on one side.
  static std::array<int, 2> lone_corner(const Orientation (&s)[3]) {
    for (int i = 0; i < 3; ++i) {
      const int sign = s[i].sign;
      if (sign != 0 && sign * s[(i + 1) % 3].sign <= 0 && sign * s[(i + 2) % 3].sign <= 0) return {i, sign};
    }
    for (int i = 0; i < 3; ++i) {
      if (s[i].sign == 0) return {i, -s[(i + 1) % 3].sign};
    }
    return {0, 0};  // not reached: the corners are neither all on one side nor all in the plane
  }

  // No shared corner (Devillers and Guigue 2002): with a's lone corner a0 and b's b0 both on the positive side of the
  // other's plane (swapping the other two corners of the other triangle flips its normal, and so that side), a meets
  // L between its edges a0 a1 (at one end along L) and a0 a2, and b between b0 b1 and b0 b2 in the opposite order;
  // the segments overlap when the two orient3d of corresponding edges say that neither lies past the other's end.
  bool segments_overlap() const {
    const auto [ia, side_a] = lone_corner(a_sides_);
    const auto [jb, side_b] = lone_corner(b_sides_);
    const Eigen::Vector3d* a1 = &a_[(ia + 1) % 3];
    const Eigen::Vector3d* a2 = &a_[(ia + 2) % 3];
    const Eigen::Vector3d* b1 = &b_[(jb + 1) % 3];
    const Eigen::Vector3d* b2 = &b_[(jb + 2) % 3];
    if (side_a < 0) std::swap(b1, b2);
    if (side_b < 0) std::swap(a1, a2);
    const Eigen::Vector3d &a0 = a_[ia], &b0 = b_[jb];
    return filter::orient3d_exact_sign(a0, *a1, b0, *b1).sign <= 0 &&
           filter::orient3d_exact_sign(a0, *a2, b0, *b2).sign >= 0;
  }

  // One shared vertex v, a corner of both segments on L, so they meet beyond it when they leave v in one direction.
  // With a = (v, a1, a2) in its cyclic order and d = n_a x n_b along L, a's segment leaves v along +d when a1 lies
  // more on the positive side of b's plane than a2 (sign(s(a1) - s(a2)) > 0; the two differ, or a would not cross b's
  // plane, or lie in it), and b's, symmetrically, along -d when sign(s(b1) - s(b2)) > 0: no further orientation.
  bool beyond_shared_vertex() const {
    const int ia = shared_.pairs[0][0], jb = shared_.pairs[0][1];
    const int toward_a = a_sides_[(ia + 1) % 3].sign - a_sides_[(ia + 2) % 3].sign;
    const int toward_b = b_sides_[(jb + 1) % 3].sign - b_sides_[(jb + 2) % 3].sign;
    return toward_a * toward_b < 0;
  }

  // An intersecting pair's crossing: an edge crossing the other's plane inside the other triangle (with a shared
  // vertex only the edges opposite it can meet the other beyond it).
  void find_crossing(TriangleContact& contact) {
    if (sharing_.count == 0) {
      for (int face = 0; face < 2; ++face) {
        for (int k = 0; k < 3; ++k) {
          if (crosses_plane_inside(face, k, contact)) return;
        }
      }
    } else {
      const int ia = shared_.pairs[0][0], jb = shared_.pairs[0][1];
      if (!crosses_plane_inside(0, (ia + 1) % 3, contact)) crosses_plane_inside(1, (jb + 1) % 3, contact);
    }
  }

  // Edge k of `face` crosses the other triangle's plane inside that triangle.
  bool crosses_plane_inside(int face, int k, TriangleContact& contact) {
    const Orientation* s = face == 0 ? a_sides_ : b_sides_;
    const int k1 = (k + 1) % 3;
    if (s[k].sign * s[k1].sign > 0 || (s[k].sign == 0 && s[k1].sign == 0)) return false;
    Orientation v[3];  // the edge's line against the other triangle's edge j
    bool positive = false, negative = false;
    for (int j = 0; j < 3; ++j) {
      v[j] = face == 0 ? edge_edge(k, j) : edge_edge(j, k);
      positive = positive || v[j].sign > 0;
      negative = negative || v[j].sign < 0;
      if (positive && negative) return false;
    }
    if constexpr (kCrossing) {
      contact.edge_face = face;
      contact.edge = k;
      contact.edge_parameter = zero_parameter(s[k], s[k1]);
      // The crossing's weight on corner j + 2 is proportional to the volume against edge j.
      contact.face_weights = normalized_weights(v[1], v[2], v[0]);
    }
    return true;
  }

  // Every corner of b is in a's plane.
  TriangleContact coplanar(const filter::PlaneFilter& plane_a) {
    axis_ = projection_axis(plane_a);
    if (axis_ < 0) return exact_intersect_triangles(a_, b_, shared_);
    if (filter::orient2d_exact_sign(b_[0], b_[1], b_[2], axis_).sign == 0) {
      return exact_intersect_triangles(a_, b_, shared_);
    }
    TriangleContact contact = coplanar_miss();
    if (sharing_.count == 2) {
      if (!folded()) return contact;
      // Folded onto each other, they overlap on their common side of the edge: only the crossing point is left.
      if constexpr (!kCrossing) {
        contact.intersect = true;
        return contact;
      }
    }
    contact.intersect = coplanar_overlap(contact);
    return contact;
  }

  // An axis along which a projects non-degenerately (its normal's component there is not zero), or -1 when a is
  // degenerate. The rounded normal's largest component is tried first.
  int projection_axis(const filter::PlaneFilter& plane_a) {
    const int first = plane_a.dominant_axis();
    for (int step = 0; step < 3; ++step) {
      const int axis = (first + step) % 3;
      Orientation o = plane_a.normal_component(axis);
      if (o.sign == kUndecided) o.sign = exact_orient2d(a_[0], a_[1], a_[2], axis);
      if (o.sign != 0) {
        a_orientation_ = o.sign;
        return axis;
      }
    }
    return -1;
  }

  // orient2d(b_j, b_j+1, a_i): a_i against b's edge j.
  const Orientation& a_against_b(int i, int j) {
    if (!a_against_b_known_[i][j]) {
      a_against_b_known_[i][j] = true;
      const int partner = sharing_.b_of_a[i];
      a_against_b_[i][j] = partner == j || partner == (j + 1) % 3
                               ? Orientation{}
                               : filter::orient2d_exact_sign(b_[j], b_[(j + 1) % 3], a_[i], axis_);
    }
    return a_against_b_[i][j];
  }

  // orient2d(a_i, a_i+1, b_j): b_j against a's edge i.
  const Orientation& b_against_a(int j, int i) {
    if (!b_against_a_known_[j][i]) {
      b_against_a_known_[j][i] = true;
      const int partner = sharing_.a_of_b[j];
      b_against_a_[j][i] = partner == i || partner == (i + 1) % 3
                               ? Orientation{}
                               : filter::orient2d_exact_sign(a_[i], a_[(i + 1) % 3], b_[j], axis_);
    }
    return b_against_a_[j][i];
  }

  // Shared edge, coplanar: b's third corner is on the same side of the edge as a's.
  bool folded() {
    int ia[2], n = 0, jb = 0;
    for (int i = 0; i < 3; ++i) {
      if (sharing_.b_of_a[i] >= 0) ia[n++] = i;
    }
    for (int j = 0; j < 3; ++j) {
      if (sharing_.a_of_b[j] < 0) jb = j;
    }
    const int edge = ia[1] == (ia[0] + 1) % 3 ? ia[0] : ia[1];  // a's edge joining the shared corners
    return b_against_a(jb, edge).sign == a_orientation_;
  }

  // Coplanar, both non-degenerate: some unshared corner in the other triangle, or two edges crossing away from the
  // shared corners.
  bool coplanar_overlap(TriangleContact& contact) {
    for (int i = 0; i < 3; ++i) {
      if (sharing_.b_of_a[i] < 0 && inside(a_against_b(i, 0), a_against_b(i, 1), a_against_b(i, 2))) {
        if constexpr (kCrossing) {
          set_corner(contact, 0, i, a_against_b(i, 0), a_against_b(i, 1), a_against_b(i, 2));
        }
        return true;
      }
    }
    for (int j = 0; j < 3; ++j) {
      if (sharing_.a_of_b[j] < 0 && inside(b_against_a(j, 0), b_against_a(j, 1), b_against_a(j, 2))) {
        if constexpr (kCrossing) {
          set_corner(contact, 1, j, b_against_a(j, 0), b_against_a(j, 1), b_against_a(j, 2));
        }
        return true;
      }
    }
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (!edges_share_corner(i, j) && edges_cross(i, j, contact)) return true;
      }
    }
    return false;
  }

  static bool inside(const Orientation& e0, const Orientation& e1, const Orientation& e2) {
    return (e0.sign >= 0 && e1.sign >= 0 && e2.sign >= 0) || (e0.sign <= 0 && e1.sign <= 0 && e2.sign <= 0);
  }

  // The crossing point is corner k of `face` (at s = 0 on its edge k); its weights on the other triangle's corner
  // j + 2 are proportional to its orientation against edge j.
  static void set_corner(TriangleContact& contact, int face, int k, const Orientation& e0, const Orientation& e1,
                         const Orientation& e2) {
    contact.edge_face = face;
    contact.edge = k;
    contact.edge_parameter = 0.0;
    contact.face_weights = normalized_weights(e1, e2, e0);
  }

  // Edge i of a and edge j of b (coplanar, not collinear) have a common point.
  bool edges_cross(int i, int j, TriangleContact& contact) {
    const Orientation &b_from = b_against_a((j + 0) % 3, i), &b_to = b_against_a((j + 1) % 3, i);
    if (b_from.sign * b_to.sign > 0 || (b_from.sign == 0 && b_to.sign == 0)) return false;
    const Orientation &a_from = a_against_b(i, j), &a_to = a_against_b((i + 1) % 3, j);
    if (a_from.sign * a_to.sign > 0) return false;
    if constexpr (kCrossing) {
      contact.edge_face = 0;
      contact.edge = i;
      contact.edge_parameter = zero_parameter(a_from, a_to);
      const double u = zero_parameter(b_from, b_to);
      double weights[3] = {0.0, 0.0, 0.0};
      weights[j] = 1.0 - u;
      weights[(j + 1) % 3] = u;
      contact.face_weights = {weights[1], weights[2]};
    }
    return true;
  }

  const Triangle& a_;
  const Triangle& b_;
  const SharedCorners& shared_;
  Sharing sharing_;
  Orientation a_sides_[3];  // a's corners against b's plane
  Orientation b_sides_[3];  // b's corners against a's plane
  Orientation edge_edge_[3][3];
  bool edge_edge_known_[3][3] = {};
  int axis_ = 0;
  int a_orientation_ = 0;  // sign of a's projection along axis_
  Orientation a_against_b_[3][3];
  bool a_against_b_known_[3][3] = {};
  Orientation b_against_a_[3][3];
  bool b_against_a_known_[3][3] = {};
};

// The crossing's point on its edge and its point by weights on the other face agree to 2^-40 of the pair's largest
// coordinate.
bool crossing_within_rounding(const Triangle& a, const Triangle& b, const TriangleContact& contact) {
  const Triangle& edge_face = contact.edge_face == 0 ? a : b;
  const Triangle& other = contact.edge_face == 0 ? b : a;
  const double s = contact.edge_parameter, w1 = contact.face_weights[0], w2 = contact.face_weights[1];
  const Eigen::Vector3d on_edge = (1.0 - s) * edge_face[contact.edge] + s * edge_face[(contact.edge + 1) % 3];
  const Eigen::Vector3d on_face = (1.0 - w1 - w2) * other[0] + w1 * other[1] + w2 * other[2];
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) largest = std::max({largest, a[k].cwiseAbs().maxCoeff(), b[k].cwiseAbs().maxCoeff()});
  return (on_edge - on_face).cwiseAbs().maxCoeff() <= 0x1p-40 * largest;
}

}  // namespace

SharedCorners shared_corners(const std::array<int, 3>& face_a, const std::array<int, 3>& face_b) {
  SharedCorners shared;
  bool paired_b[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // A repeated index pairs once: the other copy is at the same position anyway.
      if (face_a[i] == face_b[j] && !paired_b[j]) {
        paired_b[j] = true;
        shared.pairs[shared.count++] = {i, j};
        break;
      }
    }
  }
  return shared;
}

TriangleContact intersect_triangles(const Triangle& a, const Triangle& b, const SharedCorners& shared) {
  TriangleContact contact = PairTest<true>(a, b, shared).run();
  // The rounded crossing is ill-conditioned where the signs are nearly zero (an edge nearly in the other's plane, a
  // sliver): then it is taken from the exact construction instead.
  if (contact.intersect && !crossing_within_rounding(a, b, contact)) {
    const TriangleContact exact = exact_intersect_triangles(a, b, shared);
    contact.edge_face = exact.edge_face;
    contact.edge = exact.edge;
    contact.edge_parameter = exact.edge_parameter;
    contact.face_weights = exact.face_weights;
  }
  return contact;
}

bool triangles_intersect(const Triangle& a, const Triangle& b, const SharedCorners& shared) {
  return PairTest<false>(a, b, shared).run().intersect;
}

}  // namespace clothcd::geometry
