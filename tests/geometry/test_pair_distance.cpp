// The exact pair distances (geometry/pair_distance.hpp) against the GMP reference (geometry/exact_pair_distance.hpp)
// on constructed pairs: distances exactly equal to the asked one (dyadic and decimal), touching pairs on each feature,
// points one unit in the last place from the boundaries between Voronoi regions, and degenerate primitives.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "geometry/pair_distance.hpp"
#include "pair_distance_checks.hpp"

namespace {

using clothcd::DistanceType;
using clothcd::test::check_pair;
using clothcd::test::Points;
using Eigen::Vector3d;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The pair at d, just above d and just below d, with the expected membership at each.
void check_at(bool vertex_face, const Points& x, double d, bool within_at_d) {
  CHECK(check_pair(vertex_face, x, d) == within_at_d);
  check_pair(vertex_face, x, std::nextafter(d, kInfinity));
  check_pair(vertex_face, x, std::nextafter(d, 0.0));
}

// x with each coordinate of x[which] moved one unit in the last place both ways (27 variants with x itself).
std::vector<Points> ulp_neighbours(const Points& x, int which) {
  std::vector<Points> out;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        Points y = x;
        const int steps[3] = {dx, dy, dz};
        for (int axis = 0; axis < 3; ++axis)
          if (steps[axis] != 0) y[which][axis] = std::nextafter(y[which][axis], steps[axis] * kInfinity);
        out.push_back(y);
      }
  return out;
}

// The axes permuted and flipped (exact), so that no test depends on one orientation.
Points oriented(const Points& x, int orientation) {
  Points y;
  for (int i = 0; i < 4; ++i) {
    const Vector3d& v = x[i];
    Vector3d w = orientation % 3 == 0   ? v
                 : orientation % 3 == 1 ? Vector3d(v.y(), v.z(), v.x())
                                        : Vector3d(v.z(), v.x(), v.y());
    if (orientation / 3 == 1) w = Vector3d(-w.x(), w.y(), -w.z());
    y[i] = w;
  }
  return y;
}

}  // namespace

TEST_CASE("pair distance: a point exactly d above a triangle is not within d", "[pair-distance]") {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  for (int o = 0; o < 6; ++o) {
    check_at(true, oriented({Vector3d(0.25, 0.25, 0.5), t0, t1, t2}, o), 0.5, false);
    check_at(true, oriented({Vector3d(0.25, 0.25, 0.1), t0, t1, t2}, o), 0.1, false);  // the double 0.1
    // Above the plane z = 0.3: the distance is the exact difference 0.4 - 0.3 of the doubles, not the double 0.1.
    const Vector3d lift(0, 0, 0.3);
    check_pair(true, oriented({Vector3d(0.25, 0.25, 0.4), t0 + lift, t1 + lift, t2 + lift}, o), 0.1);
    check_pair(true, oriented({Vector3d(0.25, 0.25, 0.4), t0 + lift, t1 + lift, t2 + lift}, o), 0.4 - 0.3);
    // At a vertex (3, 4, 0) away and on an edge (0, 3, 4) away: distance 5.
    check_at(true, oriented({Vector3d(4, -4, 0), t0, t1, t2}, o), 5.0, false);
    check_at(true, oriented({Vector3d(0.5, -3, 4), t0, t1, t2}, o), 5.0, false);
  }
  // The pair's own rounded distance as d, at scales from 1e-6 to 1e6.
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    const Points x{Vector3d(0.2, 0.3, 0.7) * scale, Vector3d(0, 0, 0.1) * scale, Vector3d(1, 0, 0.2) * scale,
                   Vector3d(0, 1, 0.3) * scale};
    const double d = clothcd::geometry::point_triangle_distance(x[0], x[1], x[2], x[3]).distance;
    check_pair(true, x, d);
    check_pair(true, x, std::nextafter(d, 0.0));
    check_pair(true, x, std::nextafter(d, kInfinity));
  }
}

TEST_CASE("pair distance: segments exactly d apart are not within d", "[pair-distance]") {
  for (int o = 0; o < 6; ++o) {
    check_at(false, oriented({Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0.5), Vector3d(0, 1, 0.5)}, o),
             0.5, false);
    check_at(false, oriented({Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, -1, 0.1), Vector3d(0.5, 1, 0.1)}, o),
             0.1, false);
    // Vertex-vertex (3, 4) apart, vertex-edge 5 above.
    check_at(false, oriented({Vector3d(0, 0, 0), Vector3d(-1, 0, 0), Vector3d(3, 4, 0), Vector3d(4, 4, 0)}, o), 5.0,
             false);
    check_at(false, oriented({Vector3d(0, 0, 5), Vector3d(0, 0, 6), Vector3d(-1, 0, 0), Vector3d(1, 0, 0)}, o), 5.0,
             false);
  }
}

TEST_CASE("pair distance: touching pairs have distance 0 and the exact feature", "[pair-distance]") {
  const Vector3d t0(0, 0, 0), t1(2, 0, 0), t2(0, 2, 0);
  const std::pair<Vector3d, DistanceType> touches[] = {
      {Vector3d(0.5, 0.5, 0), DistanceType::PointFace}, {Vector3d(1, 0, 0), DistanceType::PointEdge0},
      {Vector3d(1, 1, 0), DistanceType::PointEdge1},    {Vector3d(0, 1, 0), DistanceType::PointEdge2},
      {Vector3d(0, 0, 0), DistanceType::PointVertex0},  {Vector3d(2, 0, 0), DistanceType::PointVertex1},
      {Vector3d(0, 2, 0), DistanceType::PointVertex2}};
  for (int o = 0; o < 6; ++o) {
    for (const auto& [p, type] : touches) {
      const Points x = oriented({p, t0, t1, t2}, o);
      check_pair(true, x, 0x1p-1074);
      const auto record = clothcd::geometry::point_triangle_distance(x[0], x[1], x[2], x[3]);
      CHECK(record.distance == 0.0);
      CHECK(record.type == type);
    }
    const Vector3d a0(-1, 0, 0), a1(1, 0, 0);
    const std::pair<Points, DistanceType> crossings[] = {
        {{a0, a1, Vector3d(0, -1, 0), Vector3d(0, 1, 0)}, DistanceType::EdgeEdge},
        {{a0, a1, Vector3d(0, 0, 0), Vector3d(0, 1, 0)}, DistanceType::EdgeVertexB0},
        {{a0, a1, Vector3d(0, 1, 0), Vector3d(0, 0, 0)}, DistanceType::EdgeVertexB1},
        {{Vector3d(0, 0, 0), Vector3d(0, 1, 1), a0, a1}, DistanceType::VertexA0Edge},
        {{Vector3d(0, 1, 1), Vector3d(0, 0, 0), a0, a1}, DistanceType::VertexA1Edge},
        {{a0, a1, a1, Vector3d(2, 1, 0)}, DistanceType::VertexA1VertexB0},
        {{a0, a1, Vector3d(2, 1, 0), a0}, DistanceType::VertexA0VertexB1}};
    for (const auto& [y, type] : crossings) {
      const Points x = oriented(y, o);
      check_pair(false, x, 0x1p-1074);
      const auto record = clothcd::geometry::segment_segment_distance(x[0], x[1], x[2], x[3]);
      CHECK(record.distance == 0.0);
      CHECK(record.type == type);
    }
  }
}

TEST_CASE("pair distance: points one ulp from the boundaries between Voronoi regions", "[pair-distance]") {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  // On the planes between regions: face | edge 0 (y = 0), face | edge 2 (x = 0), face | edge 1 (x + y = 1), edge 0 |
  // vertex 1 (x = 1), edge 0 | vertex 0 (x = 0, y < 0), edge 1 | vertex 1 (y = x - 1), and in the plane itself.
  const Vector3d boundary_points[] = {Vector3d(0.375, 0, 0.25), Vector3d(0, 0.625, 0.25), Vector3d(0.25, 0.75, 0.5),
                                      Vector3d(1, -0.5, 0.25),  Vector3d(0, -0.5, 0.25),  Vector3d(1.5, 0.5, 0.25),
                                      Vector3d(0.375, 0, 0),    Vector3d(1, -0.5, 0),     Vector3d(0.25, 0.75, 0)};
  for (int o = 0; o < 6; ++o) {
    for (const Vector3d& p : boundary_points) {
      for (const Points& x : ulp_neighbours(oriented({p, t0, t1, t2}, o), 0)) {
        check_pair(true, x, 0.25);
        check_pair(true, x, 0.5);
      }
    }
  }
  // Segments: b's end b0 over a's end a0 (corner | sides), over the middle of a (side | inside), b crossing over a's
  // end a1.
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  const Points pairs[] = {{a0, a1, Vector3d(0, 0, 0.5), Vector3d(0, 1, 0.5)},
                          {a0, a1, Vector3d(0.5, 0, 0.5), Vector3d(0.5, 1, 0.5)},
                          {a0, a1, Vector3d(1, -1, 0.25), Vector3d(1, 1, 0.25)},
                          {a0, a1, Vector3d(0, 0, 0), Vector3d(-1, 1, 0)}};
  for (int o = 0; o < 6; ++o) {
    for (const Points& y : pairs) {
      for (int which = 0; which < 4; ++which) {
        for (const Points& x : ulp_neighbours(oriented(y, o), which)) {
          check_pair(false, x, 0.25);
          check_pair(false, x, 0.5);
        }
      }
    }
  }
}

TEST_CASE("pair distance: zero-area triangles and coincident vertices", "[pair-distance]") {
  const Vector3d a(0, 0, 0), b(1, 1, 0), c(2, 2, 0);  // collinear, b between a and c
  const Vector3d probes[] = {Vector3d(0.5, 0.5, 1), Vector3d(1.5, 1.5, 0), Vector3d(1, 1, 0),       Vector3d(1, 1, 2),
                             Vector3d(-1, 0, 0),    Vector3d(3, 3, 3),     Vector3d(0.25, 0.25, 0), Vector3d(2, 2, 0)};
  const std::array<Vector3d, 3> triangles[] = {{a, b, c}, {b, a, c}, {a, c, b}, {c, a, b},
                                               {a, a, c}, {a, c, c}, {b, b, b}, {a, a, b}};
  for (int o = 0; o < 6; ++o) {
    for (const auto& t : triangles) {
      for (const Vector3d& p : probes) {
        const Points x = oriented({p, t[0], t[1], t[2]}, o);
        check_pair(true, x, 1.0);
        check_pair(true, x, 0.5);
        CHECK(clothcd::geometry::point_triangle_distance(x[0], x[1], x[2], x[3]).type != DistanceType::PointFace);
      }
    }
  }
  // A point on the middle vertex of a collinear triangle is at that vertex, though edge 2 also holds it.
  const auto record = clothcd::geometry::point_triangle_distance(b, a, b, c);
  CHECK(record.type == DistanceType::PointVertex1);
  CHECK(clothcd::geometry::point_triangle_distance(Vector3d(1, 1, 1), b, b, b).type == DistanceType::PointVertex0);
}

TEST_CASE("pair distance: parallel, collinear and zero-length segments", "[pair-distance]") {
  const Vector3d a0(0, 0, 0), a1(2, 0, 0);
  const Points pairs[] = {
      {a0, a1, Vector3d(1, 1, 0), Vector3d(3, 1, 0)},   // parallel, overlapping
      {a0, a1, Vector3d(3, 1, 0), Vector3d(1, 1, 0)},   // parallel, reversed
      {a0, a1, Vector3d(3, 1, 0), Vector3d(5, 1, 0)},   // parallel, apart along the line
      {a0, a1, Vector3d(2, 1, 0), Vector3d(4, 1, 0)},   // parallel, ends aligned
      {a0, a1, Vector3d(1, 0, 0), Vector3d(3, 0, 0)},   // collinear, overlapping
      {a0, a1, Vector3d(3, 0, 0), Vector3d(4, 0, 0)},   // collinear, apart
      {a0, a1, Vector3d(-1, 0, 0), Vector3d(3, 0, 0)},  // collinear, b holds a
      {a0, a0, Vector3d(1, 1, 0), Vector3d(3, 1, 0)},   // a is a point
      {a0, a1, Vector3d(1, 1, 0), Vector3d(1, 1, 0)},   // b is a point over a
      {a0, a0, Vector3d(1, 1, 0), Vector3d(1, 1, 0)},   // both points
      {a0, a0, a0, a0},                                 // one point
      {a0, a1, Vector3d(1, 0, 0), Vector3d(1, 0, 0)},   // b is a point on a
  };
  for (int o = 0; o < 6; ++o) {
    for (const Points& y : pairs) {
      const Points x = oriented(y, o);
      for (double d : {0.5, 1.0, std::nextafter(1.0, 2.0), 2.0}) check_pair(false, x, d);
    }
  }
  // Parallel and overlapping: the closest pairs run along the overlap. No corner holds one, nor a0 (its closest point
  // on b is b0, farther away); a1 against the inside of b is the first in the tie order.
  CHECK(clothcd::geometry::segment_segment_distance(a0, a1, Vector3d(1, 1, 0), Vector3d(3, 1, 0)).type ==
        DistanceType::VertexA1Edge);
}

TEST_CASE("pair distance: asked distances and coordinates beyond the filter's range", "[pair-distance]") {
  const Points vf{Vector3d(0.25, 0.25, 0.5), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  const Points ee{Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0.5), Vector3d(0, 1, 0.5)};
  for (bool vertex_face : {true, false}) {
    const Points& x = vertex_face ? vf : ee;
    clothcd::geometry::PairDistance out;
    const auto within = [&](double d) {
      return vertex_face ? clothcd::geometry::point_triangle_within(x[0], x[1], x[2], x[3], d, out)
                         : clothcd::geometry::segment_segment_within(x[0], x[1], x[2], x[3], d, out);
    };
    CHECK_FALSE(within(0.0));
    CHECK_FALSE(within(-1.0));
    CHECK_FALSE(within(std::numeric_limits<double>::quiet_NaN()));
    CHECK(within(kInfinity));
    CHECK(out.distance == 0.5);
    check_pair(vertex_face, x, 1e200);  // beyond the filter's 2^100: the exact tier
    // Coordinates beyond 2^100, and the same pair scaled down by 2^-200 (exact): the same decisions, scaled.
    Points huge = x, tiny = x;
    for (int i = 0; i < 4; ++i) huge[i] = x[i] * 0x1p200, tiny[i] = x[i] * 0x1p-200;
    CHECK(check_pair(vertex_face, huge, 0x1p200));
    CHECK_FALSE(check_pair(vertex_face, huge, 0x1p199));
    CHECK(check_pair(vertex_face, tiny, 0x1p-200));
    CHECK_FALSE(check_pair(vertex_face, tiny, 0x1p-201));
  }
}
