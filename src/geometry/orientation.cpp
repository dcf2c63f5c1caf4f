// The exact orientation predicates: the filters of geometry/orientation_filter.hpp, and their fallbacks in GMP
// rationals (a double converts to mpq_class exactly).
#include "geometry/orientation.hpp"

#include <gmpxx.h>

#include "geometry/orientation_filter.hpp"

namespace clothcd::geometry {

Orientation orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                     const Eigen::Vector3d& s) {
  return filter::orient3d_exact_sign(p, q, r, s);
}

Orientation orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int drop_axis) {
  return filter::orient2d_exact_sign(p, q, r, drop_axis);
}

int exact_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                   const Eigen::Vector3d& s) {
  mpq_class e1[3], e2[3], d[3];
  for (int k = 0; k < 3; ++k) {
    const mpq_class origin(p[k]);
    e1[k] = mpq_class(q[k]) - origin;
    e2[k] = mpq_class(r[k]) - origin;
    d[k] = mpq_class(s[k]) - origin;
  }
  const mpq_class det = d[0] * (e1[1] * e2[2] - e1[2] * e2[1]) + d[1] * (e1[2] * e2[0] - e1[0] * e2[2]) +
                        d[2] * (e1[0] * e2[1] - e1[1] * e2[0]);
  return sgn(det);
}

int exact_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int drop_axis) {
  const int i = (drop_axis + 1) % 3, j = (drop_axis + 2) % 3;
  const mpq_class ei = mpq_class(q[i]) - mpq_class(p[i]), ej = mpq_class(q[j]) - mpq_class(p[j]);
  const mpq_class fi = mpq_class(r[i]) - mpq_class(p[i]), fj = mpq_class(r[j]) - mpq_class(p[j]);
  return sgn(mpq_class(ei * fj - ej * fi));
}

}  // namespace clothcd::geometry
