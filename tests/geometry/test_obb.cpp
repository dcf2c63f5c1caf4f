// Oriented boxes: every method bounds every vertex it was built from (random, degenerate and real meshes), the
// simplified-model box bounds the ORIGINAL model at every pose, exact answers on boxes, calipers against brute force.
#include <catch2/catch.hpp>

#include <limits>
#include <random>

#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "geometry/min_area_rectangle.hpp"

using namespace clothcd;
using namespace clothcd::geometry;

namespace {

constexpr ObbMethod kMethods[] = {ObbMethod::Covariance, ObbMethod::FastAdaptive, ObbMethod::FastAdaptiveSimplified,
                                  ObbMethod::Tight};

void check_bounds(const Obb& box, const Vertices& points) {
  const double scale = 1.0 + points.cwiseAbs().maxCoeff();
  CHECK((box.axes.transpose() * box.axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(box.axes.determinant() == Approx(1.0));
  CHECK(box.half_extents.minCoeff() >= 0.0);
  int outside = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) outside += !box.contains(points.row(i).transpose(), 1e-12 * scale);
  CHECK(outside == 0);
}

void check_all_methods(const TriangleMesh& mesh) {
  for (ObbMethod method : kMethods) {
    CAPTURE(static_cast<int>(method));
    check_bounds(compute_obb(mesh, method), mesh.vertices);
  }
}

Eigen::Isometry3d random_pose(std::mt19937_64& random) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(n(random), n(random), n(random), n(random)).normalized().toRotationMatrix();
  pose.translation() << 5 * n(random), 5 * n(random), 5 * n(random);
  return pose;
}

}  // namespace

TEST_CASE("Every OBB method bounds random triangle soups", "[geometry][obb]") {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) check_all_methods(test::random_soup(120, seed, 2.0));
}

TEST_CASE("Every OBB method bounds degenerate point sets", "[geometry][obb]") {
  SECTION("coplanar: a flat grid") { check_all_methods(make_grid(9, 7, 2.0, 1.0)); }
  SECTION("collinear points, zero-area faces") {
    TriangleMesh line;
    line.vertices.resize(6, 3);
    for (int i = 0; i < 6; ++i) line.vertices.row(i) << i, 2.0 * i, -0.5 * i;
    line.faces.resize(4, 3);
    line.faces << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5;
    check_all_methods(line);
  }
  SECTION("a single point") {
    TriangleMesh point;
    point.vertices.resize(1, 3);
    point.vertices << 1, 2, 3;
    point.faces.resize(1, 3);
    point.faces << 0, 0, 0;
    for (ObbMethod method : kMethods) {
      const Obb box = compute_obb(point, method);
      check_bounds(box, point.vertices);
      CHECK(box.volume() == 0.0);
    }
  }
  SECTION("duplicated points") {
    TriangleMesh box = make_box(Eigen::Vector3d(1, 2, 3));
    TriangleMesh doubled;
    doubled.vertices.resize(16, 3);
    doubled.vertices << box.vertices, box.vertices;
    doubled.faces.resize(24, 3);
    doubled.faces << box.faces, (box.faces.array() + 8).matrix();
    check_all_methods(doubled);
  }
  SECTION("no vertices or a bad coordinate is an error") {
    CHECK_THROWS_AS(compute_obb(TriangleMesh{}, ObbMethod::Covariance), std::invalid_argument);
    TriangleMesh bad = make_box();
    bad.vertices(3, 1) = std::nan("");
    CHECK_THROWS_AS(compute_obb(bad, ObbMethod::Tight), std::invalid_argument);
    // Every position of the checks' partial sums and their tail, infinities of both signs, and face indices.
    const TriangleMesh soup = test::random_soup(7, 3);  // 21 coordinates: five groups of four and a tail of one
    for (Eigen::Index k = 0; k < soup.vertices.size(); ++k) {
      for (double value : {std::nan(""), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
        TriangleMesh broken = soup;
        broken.vertices.data()[k] = value;
        CHECK_THROWS_AS(compute_obb(broken, ObbMethod::Covariance), std::invalid_argument);
        CHECK_THROWS_AS(SimplifiedObb(broken), std::invalid_argument);
      }
    }
    for (int index : {-1, 7, 1 << 30}) {
      TriangleMesh broken = soup;
      broken.faces(6, 2) = index;
      CHECK_THROWS_AS(compute_obb(broken, ObbMethod::Covariance), std::invalid_argument);
    }
    CHECK_NOTHROW(compute_obb(soup, ObbMethod::Covariance));
  }
}

TEST_CASE("On a rotated box, covariance and tight find the box itself", "[geometry][obb]") {
  // A box with distinct extents has distinct covariance eigenvalues, so the axes are the box's; the tight search has
  // the box's faces among the hull faces.
  std::mt19937_64 random(11);
  TriangleMesh box = make_box(Eigen::Vector3d(1.0, 2.0, 3.0));
  const Eigen::Isometry3d pose = random_pose(random);
  box.vertices = (box.vertices * pose.linear().transpose()).rowwise() + pose.translation().transpose();
  for (ObbMethod method : {ObbMethod::Covariance, ObbMethod::Tight}) {
    CAPTURE(static_cast<int>(method));
    const Obb obb = compute_obb(box, method);
    CHECK(obb.volume() == Approx(48.0).epsilon(1e-9));
    CHECK(obb.center.isApprox(pose.translation(), 1e-9));
  }
}

TEST_CASE("Every OBB method bounds real models, and tight is the smallest", "[geometry][obb][models]") {
  for (const char* name : {"dinosaur", "cat"}) {
    CAPTURE(name);
    const TriangleMesh mesh = test::load_model(name);
    double tight = 0.0;
    double smallest_other = 1e300;
    for (ObbMethod method : kMethods) {
      const Obb box = compute_obb(mesh, method);
      check_bounds(box, mesh.vertices);
      if (method == ObbMethod::Tight) tight = box.volume();
      else smallest_other = std::min(smallest_other, box.volume());
    }
    CHECK(tight <= smallest_other * (1 + 1e-9));
    CHECK(compactness(tight, mesh) > 1.0);
  }
}

TEST_CASE("The simplified-model box bounds the original model at every pose", "[geometry][obb][simplified]") {
  const TriangleMesh mesh = test::load_model("dinosaur");
  SimplifiedObb builder(mesh);
  CHECK(builder.simplified().face_count() <= mesh.face_count() / 10 + 1);
  CHECK(builder.hull_vertex_indices().size() < static_cast<size_t>(mesh.vertex_count()));
  std::mt19937_64 random(3);
  for (int step = 0; step < 10; ++step) {
    const Eigen::Isometry3d pose = step == 0 ? Eigen::Isometry3d::Identity() : random_pose(random);
    const Vertices moved = (mesh.vertices * pose.linear().transpose()).rowwise() + pose.translation().transpose();
    check_bounds(builder.update(pose), moved);
    // A deformed model (here stretched along x): the extents come from the given vertices themselves.
    Vertices deformed = moved;
    deformed.col(0) *= 1.3;
    check_bounds(builder.update(pose, deformed), deformed);
  }
  // At rest the rebuilt box equals the one-shot (c) box.
  CHECK(builder.update(Eigen::Isometry3d::Identity()).volume() ==
        Approx(compute_obb(mesh, ObbMethod::FastAdaptiveSimplified).volume()).epsilon(1e-9));
}

TEST_CASE("The simplified-model box per update: exact extents, axes as a full rebuild", "[geometry][obb][simplified]") {
  const TriangleMesh mesh = test::load_model("dinosaur");
  ObbSettings paper;
  paper.refine_axes = false;
  ObbSettings few_slabs = paper;  // few kept vertices: their triangles are found from the vertices, not by a face scan
  few_slabs.slabs = 2;
  for (const ObbSettings& settings : {paper, few_slabs, ObbSettings{}}) {
    CAPTURE(settings.slabs, settings.refine_axes);
    SimplifiedObb builder(mesh, settings);
    std::mt19937_64 random(5);
    for (int step = 0; step < 20; ++step) {
      const Eigen::Isometry3d pose = step == 0 ? Eigen::Isometry3d::Identity() : random_pose(random);
      const Vertices moved = (mesh.vertices * pose.linear().transpose()).rowwise() + pose.translation().transpose();
      const Obb box = builder.update(pose);
      check_bounds(box, moved);
      // The support queries over the hull at rest give exactly the extents of every moved vertex on these axes.
      const Obb scanned = fit_obb_to_axes(moved, box.axes);
      const double scale = 1.0 + moved.cwiseAbs().maxCoeff();
      CHECK((box.half_extents - scanned.half_extents).cwiseAbs().maxCoeff() < 1e-12 * scale);
      CHECK((box.center - scanned.center).cwiseAbs().maxCoeff() < 1e-12 * scale);
      if (settings.refine_axes) continue;  // refinement picks among near-ties, which round-off may reorder
      // The axes equal those of the fast adaptive box of the moved simplified model rebuilt from scratch (up to sign).
      TriangleMesh simplified = builder.simplified();
      simplified.vertices =
          (simplified.vertices * pose.linear().transpose()).rowwise() + pose.translation().transpose();
      const Obb rebuilt = compute_obb(simplified, ObbMethod::FastAdaptive, settings);
      for (int k = 0; k < 3; ++k) CHECK(std::abs(box.axes.col(k).dot(rebuilt.axes.col(k))) == Approx(1.0).epsilon(1e-9));
    }
  }
}

TEST_CASE("Minimum-area rectangle matches brute force over hull edges", "[geometry][obb]") {
  std::mt19937_64 random(5);
  std::normal_distribution<double> n(0, 1);
  std::vector<Eigen::Vector2d> hull;
  for (int trial = 0; trial < 40; ++trial) {
    const int count = 3 + trial * 2;
    std::vector<Eigen::Vector2d> points(static_cast<size_t>(count));
    for (auto& p : points) p = {n(random) * 3, n(random)};
    // Brute force over every pair's direction (a superset of the hull edges).
    double brute = 1e300;
    for (const auto& a : points)
      for (const auto& b : points) {
        if ((b - a).norm() == 0) continue;
        const Eigen::Vector2d d = (b - a).normalized(), e(-d.y(), d.x());
        double u0 = 1e300, u1 = -1e300, w0 = 1e300, w1 = -1e300;
        for (const auto& p : points) {
          u0 = std::min(u0, p.dot(d)), u1 = std::max(u1, p.dot(d));
          w0 = std::min(w0, p.dot(e)), w1 = std::max(w1, p.dot(e));
        }
        brute = std::min(brute, (u1 - u0) * (w1 - w0));
      }
    const detail::Rectangle r = detail::min_area_rectangle(points, hull);
    CHECK(r.area == Approx(brute).epsilon(1e-9));
  }
}

TEST_CASE("Every OBB method gives the same box at any scale", "[geometry][obb]") {
  const TriangleMesh unit = make_uv_sphere(1.0, 8, 4);
  for (const ObbMethod method : {ObbMethod::Covariance, ObbMethod::FastAdaptive, ObbMethod::FastAdaptiveSimplified,
                                 ObbMethod::Tight}) {
    const Obb reference = compute_obb(unit, method);
    Eigen::Vector3d expected = reference.half_extents;
    std::sort(expected.data(), expected.data() + 3);
    for (const int exponent : {-900, -300, 300, 900}) {  // coordinates of about 1e-271 .. 1e271
      INFO("method " << static_cast<int>(method) << ", scale 2^" << exponent);
      TriangleMesh scaled = unit;
      scaled.vertices *= std::ldexp(1.0, exponent);
      const Obb box = compute_obb(scaled, method);
      Eigen::Vector3d half = box.half_extents * std::ldexp(1.0, -exponent);
      std::sort(half.data(), half.data() + 3);
      CHECK((half - expected).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK((box.center * std::ldexp(1.0, -exponent)).cwiseAbs().maxCoeff() <= 1e-12);
    }
  }
}

TEST_CASE("SimplifiedObb::update refuses a NaN pose and a wrong vertex count", "[geometry][obb][simplified]") {
  const TriangleMesh sphere = make_uv_sphere(1.0, 8, 4);
  SimplifiedObb box(sphere);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().x() = std::nan("");
  CHECK_THROWS_AS(box.update(pose), std::invalid_argument);
  CHECK_THROWS_AS(box.update(Eigen::Isometry3d::Identity(), sphere.vertices.topRows(3)), std::invalid_argument);
  CHECK_NOTHROW(box.update(Eigen::Isometry3d::Identity(), sphere.vertices));
}
