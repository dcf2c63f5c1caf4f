#pragma once
// A small detection step shared by the detector's tests: a 12 x 12 cloth grid falling onto a sphere.

#include <cmath>
#include <random>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::test {

/// One step of a cloth over a sphere: the cloth at the start, its end positions and the obstacle.
struct ClothOverSphere {
  TriangleMesh cloth;     ///< 12 x 12 grid, 1.6 wide, 0.62 above the sphere's centre.
  Vertices end;           ///< The cloth dropped by `drop` plus a wave of 0.1 and a seeded jitter of 0.03.
  TriangleMesh obstacle;  ///< Sphere of radius 0.6 at the origin.
};

/// The step with the cloth falling by `drop` (0.12-0.15 puts it into the sphere's top).
inline ClothOverSphere cloth_over_sphere(double drop) {
  ClothOverSphere step;
  step.cloth = make_grid(12, 12, 1.6, 1.6);
  step.cloth.vertices.col(1).array() += 0.62;
  step.obstacle = make_uv_sphere(0.6, 12, 8);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  step.end = step.cloth.vertices;
  for (Eigen::Index v = 0; v < step.end.rows(); ++v) {
    step.end(v, 1) -= drop + 0.1 * std::cos(3.0 * step.cloth.vertices(v, 0));
    for (int k = 0; k < 3; ++k) step.end(v, k) += jitter(rng);
  }
  return step;
}

}  // namespace clothcd::test
