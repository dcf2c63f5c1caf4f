// The limit on the SIMD level, and the geometry results at every level the CPU runs against those of the baseline:
// the baseline fallbacks, which the CPU check otherwise never picks on a machine with AVX2, give the same boxes (up
// to summation order) that contain every vertex.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <string>
#include <vector>

#include "clothcd/geometry/obb.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

using namespace clothcd;
using geometry::Obb;
using geometry::ObbMethod;

namespace {

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

TEST_CASE("the SIMD level follows the CPU and the limit", "[support][cpu]") {
  const std::vector<SimdLevel> levels = cpu_simd_levels();
  REQUIRE_FALSE(levels.empty());
  CHECK(levels.front() == SimdLevel::Baseline);
  CHECK(levels.back() == cpu_simd_level());
  CHECK(simd_level() == cpu_simd_level());
  for (std::size_t k = 1; k < levels.size(); ++k) CHECK(levels[k - 1] < levels[k]);
  for (const SimdLevel limit : {SimdLevel::Baseline, SimdLevel::Avx2, SimdLevel::Avx512}) {
    test::SimdLimit capped(limit);
    CHECK(simd_level() == std::min(limit, cpu_simd_level()));
  }
  CHECK(simd_level() == cpu_simd_level());
  CHECK(std::string(simd_level_name(SimdLevel::Avx2)) == "avx2");
}

TEST_CASE("OBBs at every SIMD level equal those of the baseline", "[support][cpu][geometry]") {
  const std::vector<TriangleMesh> meshes{make_fish(), make_uv_sphere(1.0, 24, 12), make_box({1.0, 0.3, 2.0})};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.translation() = Eigen::Vector3d(0.5, -2.0, 3.0);
  for (const SimdLevel level : cpu_simd_levels()) {
    INFO("level " << simd_level_name(level));
    for (const TriangleMesh& rest : meshes) {
      const TriangleMesh mesh = moved(rest, pose);
      for (const ObbMethod method : {ObbMethod::Covariance, ObbMethod::FastAdaptive, ObbMethod::FastAdaptiveSimplified}) {
        INFO("method " << static_cast<int>(method) << ", " << mesh.vertices.rows() << " vertices");
        Obb wide;
        {
          test::SimdLimit capped(level);
          wide = geometry::compute_obb(mesh, method);
        }
        test::SimdLimit baseline(SimdLevel::Baseline);
        check_same_box(wide, geometry::compute_obb(mesh, method), mesh.vertices);
      }
      // The per-step update of (c) for a moving obstacle, built and run at each level.
      Obb wide;
      {
        test::SimdLimit capped(level);
        geometry::SimplifiedObb wide_tracker(rest);
        wide = wide_tracker.update(pose);
      }
      test::SimdLimit baseline(SimdLevel::Baseline);
      geometry::SimplifiedObb baseline_tracker(rest);
      check_same_box(wide, baseline_tracker.update(pose), mesh.vertices);
    }
  }
}
