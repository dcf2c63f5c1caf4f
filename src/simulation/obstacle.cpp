// Rigid obstacle poses: a constant screw-like motion per step, x(s) = R^s (x_rest - pivot) + pivot + s t.
#include "clothcd/simulation/obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clothcd::simulation {
namespace {

Eigen::Matrix3d rotation(const RigidMotion& m, double turns) {
  if (m.axis.squaredNorm() == 0 || m.angle == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(m.angle * turns, m.axis.normalized()).toRotationMatrix();
}

}  // namespace

bool Obstacle::moves_during(int step) const { return step < motion.moving_steps; }

Vertices Obstacle::positions_at(int step) const {
  const int s = std::clamp(step, 0, motion.moving_steps);
  const Eigen::Matrix3d r = rotation(motion, s);
  const Eigen::RowVector3d centre = (motion.pivot + s * motion.translation).transpose();
  Vertices x(rest.vertices.rows(), 3);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    x.row(v) = (r * (rest.vertices.row(v) - motion.pivot.transpose()).transpose()).transpose() + centre;
  }
  return x;
}

Eigen::Vector3d Obstacle::carry(const Eigen::Vector3d& p, int step) const {
  if (!moves_during(step)) return p;
  const Eigen::Vector3d centre = motion.pivot + step * motion.translation;
  return rotation(motion, 1) * (p - centre) + centre + motion.translation;
}

TriangleMesh normalize_obstacle(const TriangleMesh& mesh, int up, double size) {
  if (up < 0 || up > 2) throw std::invalid_argument("normalize_obstacle: up axis must be 0, 1 or 2");
  if (!(size > 0) || !std::isfinite(size)) throw std::invalid_argument("normalize_obstacle: size must be > 0");
  if (mesh.vertices.rows() == 0) throw std::invalid_argument("normalize_obstacle: empty mesh");
  TriangleMesh out = mesh;
  // Rotations taking the up axis to +y: x -> y is a turn about z, z -> y a turn about x; both keep handedness.
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  if (up == 0) turn = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  if (up == 2) turn = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  out.vertices = (out.vertices * turn.transpose()).eval();
  const Eigen::RowVector3d lo = out.vertices.colwise().minCoeff(), hi = out.vertices.colwise().maxCoeff();
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0)) throw std::invalid_argument("normalize_obstacle: the mesh has zero extent");
  const Eigen::RowVector3d shift(0.5 * (lo.x() + hi.x()), lo.y(), 0.5 * (lo.z() + hi.z()));
  out.vertices = ((out.vertices.rowwise() - shift) * (size / extent)).eval();
  return out;
}

}  // namespace clothcd::simulation
