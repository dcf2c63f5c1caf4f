// The contact frame of a pair at a contact (the CCD's contact geometry): the vertex's barycentric weights on the
// triangle's plane or the edges' line parameters, from the normal equations of the least-squares fit, and the unit
// normal (face normal, or the edges' cross product) turned towards the first primitive.
#include <algorithm>
#include <cmath>

#include "geometry/pair_distance.hpp"

namespace clothcd::geometry {

namespace {

// n scaled to unit length and turned so that n . towards_first >= 0; zero when n is zero or not finite.
Eigen::Vector3d oriented_unit(Eigen::Vector3d n, const Eigen::Vector3d& towards_first) {
  const double length = n.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return Eigen::Vector3d::Zero();
  n /= length;
  return n.dot(towards_first) < 0.0 ? -n : n;
}

}  // namespace

ContactFrame point_triangle_contact_frame(const std::array<Eigen::Vector3d, 4>& x,
                                          const Eigen::Vector3d& towards_first) {
  ContactFrame frame;
  const Eigen::Vector3d e1 = x[2] - x[1];
  const Eigen::Vector3d e2 = x[3] - x[1];
  const Eigen::Vector3d r = x[0] - x[1];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (det > 0.0) {
    const double w1 = (d22 * e1.dot(r) - d12 * e2.dot(r)) / det;
    const double w2 = (d11 * e2.dot(r) - d12 * e1.dot(r)) / det;
    frame.parameters = {w1, w2};
  }
  frame.normal = oriented_unit(e1.cross(e2), towards_first);
  return frame;
}

ContactFrame segment_segment_contact_frame(const std::array<Eigen::Vector3d, 4>& x,
                                           const Eigen::Vector3d& towards_first) {
  ContactFrame frame;
  const Eigen::Vector3d da = x[1] - x[0];
  const Eigen::Vector3d db = x[3] - x[2];
  const Eigen::Vector3d r = x[0] - x[2];
  const double a = da.dot(da), b = da.dot(db), c = db.dot(db), d = da.dot(r), e = db.dot(r);
  const double det = a * c - b * b;
  if (det > 0.0) {
    const double s = std::clamp((b * e - c * d) / det, 0.0, 1.0);
    const double u = std::clamp((a * e - b * d) / det, 0.0, 1.0);
    frame.parameters = {s, u};
  }
  frame.normal = oriented_unit(da.cross(db), towards_first);
  return frame;
}

}  // namespace clothcd::geometry
