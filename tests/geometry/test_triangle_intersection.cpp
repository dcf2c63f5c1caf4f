// The triangle intersection test on configurations with known answers: crossing, touching at a vertex, an edge or a
// face, coplanar overlaps and touches, parallel and collinear edges, shared vertices and edges, duplicated faces and
// degenerate triangles. Each is checked against its expected answer and against the rational reference, with the
// reported crossing point checked on both faces.
#include <catch2/catch.hpp>

#include "geometry/triangle_pair_checks.hpp"

using namespace clothcd;
using namespace clothcd::test;

namespace {

using V = Eigen::Vector3d;

// The base triangle in the plane z = 0.
const Triangle kBase = {V(0, 0, 0), V(4, 0, 0), V(0, 4, 0)};

struct Case {
  const char* name;
  Triangle a, b;
  SharedCorners shared;
  bool intersect;
  bool coplanar;
};

void check(const Case& c) {
  INFO(c.name);
  const TriangleContact contact = geometry::intersect_triangles(c.a, c.b, c.shared);
  CHECK(contact.intersect == c.intersect);
  CHECK(contact.coplanar == c.coplanar);
  CHECK(disagreement(c.a, c.b, c.shared) == "");
  // The roles swapped: b against a, the pairs reversed.
  SharedCorners swapped = c.shared;
  for (int k = 0; k < swapped.count; ++k) std::swap(swapped.pairs[k][0], swapped.pairs[k][1]);
  CHECK(geometry::intersect_triangles(c.b, c.a, swapped).intersect == c.intersect);
  CHECK(disagreement(c.b, c.a, swapped) == "");
}

}  // namespace

TEST_CASE("triangles crossing, touching and apart in space", "[geometry][triangle-intersection]") {
  const Case cases[] = {
      {"apart above", kBase, {V(0, 0, 1), V(1, 0, 2), V(0, 1, 3)}, {}, false, false},
      {"parallel planes", kBase, {V(0, 0, 1), V(4, 0, 1), V(0, 4, 1)}, {}, false, false},
      {"piercing", kBase, {V(1, 1, -1), V(1, 1, 1), V(3, 3, 0)}, {}, true, false},
      {"crossing through an edge", kBase, {V(2, -1, -1), V(2, 1, 1), V(2, -1, 1)}, {}, true, false},
      {"vertex on the face", kBase, {V(1, 1, 0), V(1, 1, 2), V(2, 1, 2)}, {}, true, false},
      {"vertex on an edge", kBase, {V(2, 0, 0), V(2, -1, 2), V(3, -1, 2)}, {}, true, false},
      {"vertex on a vertex", kBase, {V(4, 0, 0), V(5, 0, 2), V(5, 1, 2)}, {}, true, false},
      {"vertex just off the face", kBase, {V(1, 1, 1e-300), V(1, 1, 2), V(2, 1, 2)}, {}, false, false},
      {"edge touching an edge", kBase, {V(2, -1, 0), V(2, 1, 0), V(2, 0, 3)}, {}, true, false},
      {"edge across an edge, apart", kBase, {V(5, -1, 0), V(5, 1, 0), V(5, 0, 3)}, {}, false, false},
      {"edges on one line, overlapping", kBase, {V(3, 0, 0), V(6, 0, 0), V(4, 0, 2)}, {}, true, false},
      {"edges on one line, apart", kBase, {V(5, 0, 0), V(6, 0, 0), V(5, 0, 2)}, {}, false, false},
      {"edges on one line, end to end", kBase, {V(4, 0, 0), V(6, 0, 0), V(5, 0, 2)}, {}, true, false},
      {"edge in the plane, outside", kBase, {V(5, 5, 0), V(6, 4, 0), V(5, 5, 2)}, {}, false, false},
      {"edge in the plane, inside", kBase, {V(1, 1, 0), V(2, 1, 0), V(1, 1, 2)}, {}, true, false},
      {"through the face, hitting nothing of the boundary",
       kBase,
       {V(1, 1, -1), V(1, 1, 1), V(-5, -5, 0)},
       {},
       true,
       false},
  };
  for (const Case& c : cases) check(c);
}

TEST_CASE("coplanar triangles overlapping, touching and apart", "[geometry][triangle-intersection]") {
  const Case cases[] = {
      {"overlapping", kBase, {V(1, 1, 0), V(5, 1, 0), V(1, 5, 0)}, {}, true, true},
      {"one inside the other", kBase, {V(1, 1, 0), V(2, 1, 0), V(1, 2, 0)}, {}, true, true},
      {"star of David", {V(0, 0, 0), V(6, 0, 0), V(3, 6, 0)}, {V(0, 4, 0), V(6, 4, 0), V(3, -2, 0)}, {}, true, true},
      {"touching along an edge", kBase, {V(1, 0, 0), V(3, 0, 0), V(2, -3, 0)}, {}, true, true},
      {"touching at a vertex", kBase, {V(4, 0, 0), V(6, 0, 0), V(5, -3, 0)}, {}, true, true},
      {"vertex on an edge", kBase, {V(2, 2, 0), V(5, 5, 0), V(6, 3, 0)}, {}, true, true},
      {"apart", kBase, {V(3, 3, 0), V(6, 3, 0), V(3, 6, 0)}, {}, false, true},
      {"apart, edges parallel", kBase, {V(5, 0, 0), V(9, 0, 0), V(5, 4, 0)}, {}, false, true},
      {"a tilted plane", {V(0, 0, 0), V(4, 0, 4), V(0, 4, 4)}, {V(1, 1, 2), V(5, 1, 6), V(1, 5, 6)}, {}, true, true},
      {"a tilted plane, apart",
       {V(0, 0, 0), V(4, 0, 4), V(0, 4, 4)},
       {V(3, 3, 6), V(6, 3, 9), V(3, 6, 9)},
       {},
       false,
       true},
  };
  for (const Case& c : cases) check(c);
}

TEST_CASE("faces sharing a vertex intersect only beyond it", "[geometry][triangle-intersection]") {
  const Case cases[] = {
      {"opposite edge piercing", kBase, {V(0, 0, 0), V(2, 1, -1), V(1, 2, 1)}, share({0, -1, -1}), true, false},
      {"touching only at the vertex", kBase, {V(0, 0, 0), V(-2, 1, 1), V(-1, -2, 1)}, share({0, -1, -1}), false, false},
      {"fan around the vertex", kBase, {V(0, 0, 0), V(-4, 0, 0), V(0, -4, 0)}, share({0, -1, -1}), false, true},
      {"coplanar, overlapping around the vertex",
       kBase,
       {V(0, 0, 0), V(4, 4, 0), V(-1, 4, 0)},
       share({0, -1, -1}),
       true,
       true},
      {"coplanar, along a common edge line",
       kBase,
       {V(0, 0, 0), V(2, 0, 0), V(1, -3, 0)},
       share({0, -1, -1}),
       true,
       true},
      {"edge through the vertex in a plane",
       kBase,
       {V(0, 0, 0), V(-1, -1, 0), V(-1, -1, 3)},
       share({0, -1, -1}),
       false,
       false},
      {"opposite edge touching the face", kBase, {V(0, 0, 0), V(1, 1, 0), V(1, 1, 3)}, share({0, -1, -1}), true, false},
      {"second corner shared", kBase, {V(1, 1, -1), V(4, 0, 0), V(1, 1, 1)}, share({-1, 1, -1}), true, false},
  };
  for (const Case& c : cases) check(c);
}

TEST_CASE("faces sharing an edge intersect only when folded onto each other", "[geometry][triangle-intersection]") {
  const Case cases[] = {
      {"flat, opposite sides", kBase, {V(4, 0, 0), V(0, 0, 0), V(2, -3, 0)}, share({1, 0, -1}), false, true},
      {"folded flat", kBase, {V(4, 0, 0), V(0, 0, 0), V(1, 1, 0)}, share({1, 0, -1}), true, true},
      {"folded flat, beyond the other", kBase, {V(4, 0, 0), V(0, 0, 0), V(3, 6, 0)}, share({1, 0, -1}), true, true},
      {"dihedral angle", kBase, {V(4, 0, 0), V(0, 0, 0), V(1, 1, 1)}, share({1, 0, -1}), false, false},
      {"nearly folded", kBase, {V(4, 0, 0), V(0, 0, 0), V(1, 1, 1e-300)}, share({1, 0, -1}), false, false},
      {"duplicated face", kBase, kBase, share({0, 1, 2}), false, true},
      {"duplicated face, reversed", kBase, {kBase[2], kBase[1], kBase[0]}, share({2, 1, 0}), false, true},
  };
  for (const Case& c : cases) check(c);
}

TEST_CASE("degenerate triangles intersect as their segments or points", "[geometry][triangle-intersection]") {
  const Triangle segment_through = {V(1, 1, -1), V(1, 1, 1), V(1, 1, 0.5)};
  const Triangle point_on_face = {V(1, 1, 0), V(1, 1, 0), V(1, 1, 0)};
  const Case cases[] = {
      {"segment piercing", kBase, segment_through, {}, true, false},
      {"segment above", kBase, {V(1, 1, 1), V(1, 1, 3), V(1, 1, 2)}, {}, false, false},
      {"point on the face", kBase, point_on_face, {}, true, true},
      {"point off the face", kBase, {V(1, 1, 1), V(1, 1, 1), V(1, 1, 1)}, {}, false, false},
      {"segment in the plane, crossing an edge", kBase, {V(-1, 1, 0), V(1, 1, 0), V(0, 1, 0)}, {}, true, true},
      {"segment in the plane, outside", kBase, {V(3, 3, 0), V(5, 5, 0), V(4, 4, 0)}, {}, false, true},
      {"two segments crossing",
       {V(0, 0, 0), V(2, 2, 0), V(1, 1, 0)},
       {V(0, 2, 0), V(2, 0, 0), V(1, 1, 0)},
       {},
       true,
       true},
      {"two skew segments",
       {V(0, 0, 0), V(2, 2, 0), V(1, 1, 0)},
       {V(0, 2, 1), V(2, 0, 1), V(1, 1, 1)},
       {},
       false,
       false},
      {"two points, equal", point_on_face, point_on_face, {}, true, true},
      {"two points, apart", point_on_face, {V(1, 2, 0), V(1, 2, 0), V(1, 2, 0)}, {}, false, true},
      {"point on a segment's line, beyond it",
       {V(0, 0, 0), V(2, 2, 0), V(1, 1, 0)},
       {V(3, 3, 0), V(3, 3, 0), V(3, 3, 0)},
       {},
       false,
       true},
      {"point on a segment",
       {V(0, 0, 0), V(2, 2, 0), V(1, 1, 0)},
       {V(1.5, 1.5, 0), V(1.5, 1.5, 0), V(1.5, 1.5, 0)},
       {},
       true,
       true},
      {"collinear corner on the shared edge's line",
       kBase,
       {V(4, 0, 0), V(0, 0, 0), V(6, 0, 0)},
       share({1, 0, -1}),
       false,
       true},
      {"both along the shared edge's line, beyond it",
       {V(0, 0, 0), V(4, 0, 0), V(6, 0, 0)},
       {V(4, 0, 0), V(0, 0, 0), V(5, 0, 0)},
       share({1, 0, -1}),
       true,
       true},
      {"both along the shared edge's line, opposite ends",
       {V(0, 0, 0), V(4, 0, 0), V(6, 0, 0)},
       {V(4, 0, 0), V(0, 0, 0), V(-1, 0, 0)},
       share({1, 0, -1}),
       false,
       true},
      {"segment sharing a vertex, through the face",
       kBase,
       {V(0, 0, 0), V(2, 1, 0), V(4, 2, 0)},
       share({0, -1, -1}),
       true,
       true},
      {"segment sharing a vertex, leaving the face",
       kBase,
       {V(0, 0, 0), V(-2, -1, 0), V(-4, -2, 0)},
       share({0, -1, -1}),
       false,
       true},
  };
  for (const Case& c : cases) check(c);
}

TEST_CASE("shared corners from face indices", "[geometry][triangle-intersection]") {
  const SharedCorners edge = geometry::shared_corners({3, 7, 9}, {9, 3, 12});
  REQUIRE(edge.count == 2);
  CHECK(edge.pairs[0] == std::array<int, 2>{0, 1});
  CHECK(edge.pairs[1] == std::array<int, 2>{2, 0});
  CHECK(geometry::shared_corners({1, 2, 3}, {4, 5, 6}).count == 0);
  CHECK(geometry::shared_corners({1, 2, 3}, {3, 1, 2}).count == 3);
  // A repeated index pairs each corner of the other face once.
  CHECK(geometry::shared_corners({5, 5, 6}, {5, 8, 9}).count == 1);
}
