// QEM simplification: targets, manifoldness and orientation, open boundaries held in place, non-edge joins,
// hand-made cases, invalid settings.
#include <catch2/catch.hpp>

#include <cmath>

#include "clothcd/geometry/hausdorff.hpp"
#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_info.hpp"
#include "geometry/geometry_test_helpers.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

SimplifySettings to_faces(int faces) {
  SimplifySettings s;
  s.target_faces = faces;
  return s;
}

// On a convex closed shape centred at `centre`, every outward face normal points away from the centre.
int faces_facing_inwards(const TriangleMesh& mesh, const Eigen::Vector3d& centre) {
  int inwards = 0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose(),
                          b = mesh.vertices.row(mesh.faces(f, 1)).transpose(),
                          c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    inwards += (b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) <= 0;
  }
  return inwards;
}

}  // namespace

TEST_CASE("QEM on a UV sphere: target hit, closed, oriented, no flipped face", "[geometry][qem]") {
  const TriangleMesh sphere = make_uv_sphere(1.0, 48, 24);
  for (int target : {1000, 400, 100, 40}) {
    CAPTURE(target);
    const SimplifyResult r = simplify_qem(sphere, to_faces(target));
    CHECK(r.reached_target);
    CHECK(r.faces_after <= target);
    CHECK(r.faces_after >= target - 2);  // a closed-mesh contraction removes two faces
    CHECK(r.faces_before == sphere.face_count());
    const MeshInfo info = compute_mesh_info(r.mesh);
    CHECK(info.watertight);
    CHECK(info.degenerate_faces == 0);
    CHECK(test::is_oriented_manifold(r.mesh));
    CHECK(faces_facing_inwards(r.mesh, Eigen::Vector3d::Zero()) == 0);
    CHECK(mesh_volume(r.mesh) > 0.5 * mesh_volume(sphere));
  }
}

TEST_CASE("QEM by ratio and by error bound", "[geometry][qem]") {
  const TriangleMesh fish = make_fish();
  SimplifySettings ratio;
  ratio.target_ratio = 0.25;
  const SimplifyResult r = simplify_qem(fish, ratio);
  CHECK(r.faces_after <= static_cast<int>(std::ceil(0.25 * fish.face_count())));
  CHECK(test::is_oriented_manifold(r.mesh));
  CHECK(compute_mesh_info(r.mesh).watertight);
  // An error bound alone: tighter bounds keep more faces, and the reported error respects the bound.
  SimplifySettings loose, tight;
  loose.max_error = 0.02;
  tight.max_error = 0.002;
  const SimplifyResult l = simplify_qem(fish, loose), t = simplify_qem(fish, tight);
  CHECK(l.max_error <= 0.02);
  CHECK(t.max_error <= 0.002);
  CHECK(t.faces_after > l.faces_after);
  CHECK(l.faces_after < fish.face_count());
}

TEST_CASE("QEM keeps an open grid's boundary in place", "[geometry][qem][boundary]") {
  // A flat 2 x 2 square: every interior collapse is free, so without the penalty planes the outline would erode.
  const TriangleMesh grid = make_grid(21, 21, 2.0, 2.0);
  const SimplifyResult r = simplify_qem(grid, to_faces(60));
  CHECK(r.faces_after <= 60);
  CHECK(test::is_oriented_manifold(r.mesh));
  const MeshInfo info = compute_mesh_info(r.mesh);
  // The square's area is kept exactly when the outline stays on the square.
  CHECK(info.surface_area == Approx(4.0).epsilon(1e-9));
  CHECK(r.mesh.vertices.col(1).cwiseAbs().maxCoeff() < 1e-12);  // still flat
  // All four corners survive.
  for (double x : {-1.0, 1.0})
    for (double z : {-1.0, 1.0}) {
      bool found = false;
      for (Eigen::Index v = 0; v < r.mesh.vertex_count(); ++v)
        found = found || (r.mesh.vertices.row(v) - Eigen::RowVector3d(x, 0, z)).norm() < 1e-9;
      CHECK(found);
    }
  // Every boundary edge of the result lies on the square's outline.
  const test::EdgeCounts counts = test::count_edges(r.mesh);
  for (const auto& [edge, n] : counts.undirected) {
    if (n != 1) continue;
    const Eigen::RowVector3d a = r.mesh.vertices.row(edge.first), b = r.mesh.vertices.row(edge.second);
    const bool on_x = std::abs(std::abs(a.x()) - 1) < 1e-9 && std::abs(b.x() - a.x()) < 1e-9;
    const bool on_z = std::abs(std::abs(a.z()) - 1) < 1e-9 && std::abs(b.z() - a.z()) < 1e-9;
    CHECK((on_x || on_z));
  }
}

TEST_CASE("QEM hand-made cases", "[geometry][qem]") {
  SECTION("a tetrahedron cannot lose a face: any contraction would leave two coincident faces") {
    TriangleMesh tetra;
    tetra.vertices.resize(4, 3);
    tetra.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    tetra.faces.resize(4, 3);
    tetra.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
    const SimplifyResult r = simplify_qem(tetra, to_faces(2));
    CHECK_FALSE(r.reached_target);
    CHECK(r.faces_after == 4);
  }
  SECTION("a flat hexagonal fan loses its centre for free and stays flat") {
    // Centre 0 and a ring of 6: contracting the centre into a ring vertex costs 0 (all faces coplanar) and keeps the
    // outline, so the hexagon's area is exact.
    TriangleMesh fan;
    fan.vertices.resize(7, 3);
    fan.vertices.row(0) << 0, 0, 0;
    for (int i = 0; i < 6; ++i) fan.vertices.row(i + 1) << std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0;
    fan.faces.resize(6, 3);
    for (int i = 0; i < 6; ++i) fan.faces.row(i) << 0, i + 1, (i + 1) % 6 + 1;
    const SimplifyResult r = simplify_qem(fan, to_faces(4));
    CHECK(r.faces_after == 4);
    CHECK(r.max_error < 1e-9);
    CHECK(compute_mesh_info(r.mesh).surface_area == Approx(compute_mesh_info(fan).surface_area));
    CHECK(r.mesh.vertices.col(2).cwiseAbs().maxCoeff() < 1e-12);
  }
  SECTION("an edge of 258 faces stays locked: its face count saturates at 255 and does not wrap to 2") {
    // Faces (0, 1, apex i) around the edge 0-1: a non-manifold edge, so 0 and 1 never move, and every pair touches
    // them (apexes share no edge): nothing can be contracted.
    constexpr int kFaces = 258;
    TriangleMesh book;
    book.vertices.resize(kFaces + 2, 3);
    book.vertices.row(0) << 0, 0, 0;
    book.vertices.row(1) << 1, 0, 0;
    book.faces.resize(kFaces, 3);
    for (int i = 0; i < kFaces; ++i) {
      const double angle = 2 * M_PI * i / kFaces;
      book.vertices.row(i + 2) << 0.5, std::cos(angle), std::sin(angle);
      book.faces.row(i) << 0, 1, i + 2;
    }
    const SimplifyResult r = simplify_qem(book, to_faces(kFaces / 2));
    CHECK(r.contractions == 0);
    CHECK(r.faces_after == kFaces);
    CHECK_FALSE(r.reached_target);
  }
}

TEST_CASE("QEM non-edge pairs join nearby separate parts", "[geometry][qem][non-edge]") {
  // Two coarse spheres 0.05 apart: edges alone keep two components; a 0.1 threshold lets the close poles merge.
  TriangleMesh a = make_uv_sphere(1.0, 12, 6), b = a;
  b.vertices.col(0).array() += 2.05;
  TriangleMesh both;
  both.vertices.resize(a.vertex_count() * 2, 3);
  both.vertices << a.vertices, b.vertices;
  both.faces.resize(a.face_count() * 2, 3);
  both.faces << a.faces, (a.faces.array() + int(a.vertex_count())).matrix();
  SimplifySettings edges_only, joining;
  edges_only.target_ratio = joining.target_ratio = 0.7;
  joining.non_edge_threshold = 0.1;
  CHECK(compute_mesh_info(simplify_qem(both, edges_only).mesh).components == 2);
  CHECK(compute_mesh_info(simplify_qem(both, joining).mesh).components == 1);
}

TEST_CASE("QEM on real models keeps manifoldness and orientation", "[geometry][qem][models]") {
  for (const char* name : {"dinosaur", "cow"}) {
    CAPTURE(name);
    const TriangleMesh mesh = test::load_model(name);
    const MeshInfo before = compute_mesh_info(mesh);
    SimplifySettings s;
    s.target_ratio = 0.1;
    const SimplifyResult r = simplify_qem(mesh, s);
    CHECK(r.reached_target);
    const MeshInfo after = compute_mesh_info(r.mesh);
    CHECK(after.non_manifold_edges == 0);
    CHECK(after.degenerate_faces == 0);
    CHECK(after.boundary_edges <= before.boundary_edges);
    CHECK(test::is_oriented_manifold(r.mesh));
    // Close to the input: within 5% of the bounding-box diagonal both ways (the cow keeps only 580 faces).
    const double diagonal = (before.bbox_max - before.bbox_min).norm();
    HausdorffSettings h;
    h.samples = 5000;
    CHECK(hausdorff_distance(mesh, r.mesh, h) < 0.05 * diagonal);
  }
}

TEST_CASE("QEM on the bunny to 10%", "[geometry][qem][models][bunny]") {
  const TriangleMesh rabbit = test::load_model("rabbit");
  SimplifySettings s;
  s.target_ratio = 0.1;
  const SimplifyResult r = simplify_qem(rabbit, s);
  CHECK(r.faces_after <= 7541);
  CHECK(compute_mesh_info(r.mesh).watertight == compute_mesh_info(rabbit).watertight);
  CHECK(test::is_oriented_manifold(r.mesh));
}

TEST_CASE("QEM rejects bad settings and bad meshes", "[geometry][qem]") {
  const TriangleMesh sphere = make_uv_sphere();
  CHECK_THROWS_AS(simplify_qem(sphere, SimplifySettings{}), std::invalid_argument);
  SimplifySettings s;
  s.target_ratio = 1.5;
  CHECK_THROWS_AS(simplify_qem(sphere, s), std::invalid_argument);
  s.target_ratio = std::nan("");  // not "unset": it used to simplify the mesh away
  CHECK_THROWS_AS(simplify_qem(sphere, s), std::invalid_argument);
  s.target_ratio = 0.5;
  s.non_edge_threshold = -1;
  CHECK_THROWS_AS(simplify_qem(sphere, s), std::invalid_argument);
  TriangleMesh bad = sphere;
  bad.faces(0, 0) = 100000;
  CHECK_THROWS(simplify_qem(bad, to_faces(10)));
}
