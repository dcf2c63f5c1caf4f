// OBB axes of a hierarchy node. Nodes of at least kAdaptiveFaces triangles use the geometry area's fast adaptive OBB
// (Jin et al., eqs. 11-18) on the node's triangles at t0 and t1; smaller nodes use the principal axes of the vertex
// covariance (Gottschalk et al. 1996, "OBBTree"). Either way only the axes are taken: the hierarchy projects the swept
// boxes onto them, so the box bounds its contents whatever the axes are.
#include "node_obb_axes.hpp"

#include <unordered_map>

#include "clothcd/geometry/obb.hpp"

namespace clothcd::broadphase::detail {
namespace {

constexpr long kAdaptiveFaces = 16;

Eigen::Matrix3d covariance_axes(const NodeTriangles& node) {
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
  return axes;
}

// The node's triangles at t0 followed by the same triangles at t1, as one mesh.
TriangleMesh node_mesh(const NodeTriangles& node) {
  std::unordered_map<int, int> local;
  const long face_count = node.faces_end - node.faces_begin;
  TriangleMesh mesh;
  mesh.faces.resize(2 * face_count, 3);
  std::vector<int> used;
  for (long i = 0; i < face_count; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int v = node.topology->faces(node.faces_begin[i], k);
      const auto [it, inserted] = local.emplace(v, static_cast<int>(used.size()));
      if (inserted) used.push_back(v);
      mesh.faces(i, k) = it->second;
    }
  }
  const int n = static_cast<int>(used.size());
  mesh.vertices.resize(2 * n, 3);
  for (int j = 0; j < n; ++j) {
    mesh.vertices.row(j) = node.start->row(used[j]);
    mesh.vertices.row(n + j) = node.end->row(used[j]);
  }
  mesh.faces.bottomRows(face_count) = mesh.faces.topRows(face_count).array() + n;
  return mesh;
}

Eigen::Matrix3d orthonormalize(Eigen::Matrix3d axes) {
  axes.col(0).normalize();
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  axes.col(1) = axes.col(2).cross(axes.col(0)).normalized();
  return axes;
}

}  // namespace

Eigen::Matrix3d node_obb_axes(const NodeTriangles& node) {
  Eigen::Matrix3d axes = covariance_axes(node);
  if (node.faces_end - node.faces_begin >= kAdaptiveFaces) {
    try {
      const geometry::Obb obb = geometry::compute_obb(node_mesh(node), geometry::ObbMethod::FastAdaptive);
      if (obb.axes.allFinite()) axes = obb.axes;
    } catch (const std::invalid_argument&) {
      // Degenerate node (e.g. zero area): the covariance axes stand.
    }
  }
  axes = orthonormalize(axes);
  return axes.allFinite() ? axes : Eigen::Matrix3d::Identity();
}

}  // namespace clothcd::broadphase::detail
