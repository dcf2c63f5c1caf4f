// Separating axis test of an axis-aligned box against an oriented box (Gottschalk et al. 1996).
#include "geometry/box_obb_overlap.hpp"

#include <cmath>

namespace clothcd::geometry {

bool box_obb_overlap(const double (&box_min)[3], const double (&box_max)[3], const Obb& obb) {
  const Eigen::Vector3d ca(0.5 * (box_min[0] + box_max[0]), 0.5 * (box_min[1] + box_max[1]),
                           0.5 * (box_min[2] + box_max[2]));
  const Eigen::Vector3d ea(0.5 * (box_max[0] - box_min[0]), 0.5 * (box_max[1] - box_min[1]),
                           0.5 * (box_max[2] - box_min[2]));
  const Eigen::Matrix3d& r = obb.axes;
  const Eigen::Matrix3d abs_r = r.cwiseAbs().array() + 1e-9;
  const Eigen::Vector3d t = obb.center - ca;
  const Eigen::Vector3d& eb = obb.half_extents;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + eb.dot(abs_r.row(i).transpose())) return false;
  }
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(r.col(j))) > ea.dot(abs_r.col(j)) + eb[j]) return false;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const double rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      if (std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}

}  // namespace clothcd::geometry
