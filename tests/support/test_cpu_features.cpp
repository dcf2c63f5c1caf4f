// The switch that turns the AVX2/AVX-512 paths off, and the geometry results with the paths off against those with
// them on: the baseline fallbacks, which the CPU check otherwise never picks on a machine with AVX2, give the same
// boxes (up to summation order) that contain every vertex.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "clothcd/cpu_features.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;
using geometry::Obb;
using geometry::ObbMethod;

namespace {

// Turns the wide paths off for its lifetime.
struct BaselineOnly {
  BaselineOnly() { set_wide_paths_enabled(false); }
  ~BaselineOnly() { set_wide_paths_enabled(true); }
  BaselineOnly(const BaselineOnly&) = delete;
  BaselineOnly& operator=(const BaselineOnly&) = delete;
};

void check_same_box(const Obb& wide, const Obb& baseline, const Vertices& points) {
  const double scale = 1e-9 * (1.0 + wide.half_extents.norm());
  CHECK((wide.center - baseline.center).norm() <= scale);
  CHECK((wide.half_extents - baseline.half_extents).norm() <= scale);
  // Axes may differ in sign (eigenvector orientation): compare |cos| of matching columns.
  for (int k = 0; k < 3; ++k) CHECK(std::abs(wide.axes.col(k).dot(baseline.axes.col(k))) >= 1.0 - 1e-9);
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const Eigen::Vector3d p = points.row(v).transpose();
    CHECK(baseline.contains(p, 1e-12 * (1.0 + p.norm())));
  }
}

TriangleMesh moved(const TriangleMesh& mesh, const Eigen::Isometry3d& pose) {
  TriangleMesh out = mesh;
  for (Eigen::Index v = 0; v < out.vertices.rows(); ++v)
    out.vertices.row(v) = (pose * Eigen::Vector3d(mesh.vertices.row(v).transpose())).transpose();
  return out;
}

}  // namespace

TEST_CASE("the wide paths can be switched off and on", "[support][cpu]") {
  const bool avx2 = avx2_supported(), avx512 = avx512_supported();
  {
    BaselineOnly baseline;
    CHECK_FALSE(avx2_supported());
    CHECK_FALSE(avx512_supported());
  }
  CHECK(avx2_supported() == avx2);
  CHECK(avx512_supported() == avx512);
}

TEST_CASE("OBBs on the baseline paths equal those on the wide paths", "[support][cpu][geometry]") {
  const std::vector<TriangleMesh> meshes{make_fish(), make_uv_sphere(1.0, 24, 12), make_box({1.0, 0.3, 2.0})};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.translation() = Eigen::Vector3d(0.5, -2.0, 3.0);
  for (const TriangleMesh& rest : meshes) {
    const TriangleMesh mesh = moved(rest, pose);
    for (const ObbMethod method : {ObbMethod::Covariance, ObbMethod::FastAdaptive, ObbMethod::FastAdaptiveSimplified}) {
      INFO("method " << static_cast<int>(method) << ", " << mesh.vertices.rows() << " vertices");
      const Obb wide = geometry::compute_obb(mesh, method);
      BaselineOnly baseline;
      check_same_box(wide, geometry::compute_obb(mesh, method), mesh.vertices);
    }
    // The per-step update of (c) for a moving obstacle, built and run on each path.
    geometry::SimplifiedObb wide_tracker(rest);
    const Obb wide = wide_tracker.update(pose);
    BaselineOnly baseline;
    geometry::SimplifiedObb baseline_tracker(rest);
    check_same_box(wide, baseline_tracker.update(pose), mesh.vertices);
  }
}
