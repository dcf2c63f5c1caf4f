// OBB axes of a hierarchy node: principal axes of the covariance of the node's triangle vertices at t0 and t1
// (Gottschalk et al. 1996, "OBBTree"). Degenerate spreads fall back to any orthonormal basis the solver returns.
#include "node_obb_axes.hpp"

namespace clothcd::broadphase::detail {

Eigen::Matrix3d node_obb_axes(const NodeTriangles& node) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  double count = 0;
  for (const int* f = node.faces_begin; f != node.faces_end; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = node.topology->faces(*f, k);
      for (const Vertices* positions : {node.start, node.end}) {
        const Eigen::Vector3d p = positions->row(v).transpose();
        sum += p;
        second += p * p.transpose();
        count += 1;
      }
    }
  }
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d covariance = second / count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  if (solver.info() == Eigen::Success && solver.eigenvectors().allFinite()) axes = solver.eigenvectors();
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  axes.col(1) = axes.col(2).cross(axes.col(0)).normalized();
  axes.col(0).normalize();
  return axes;
}

}  // namespace clothcd::broadphase::detail
