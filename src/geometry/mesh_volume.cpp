// Enclosed volume by the divergence theorem (sum of signed tetrahedra a . (b x c) / 6 against the origin) and the
// compactness ratio tau = V(box) / V(model) of Jin et al. eqs. 19-21.
#include "clothcd/geometry/mesh_volume.hpp"

#include <cmath>
#include <stdexcept>

namespace clothcd::geometry {

double mesh_volume(const TriangleMesh& mesh) {
  if (mesh.face_count() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertex_count()))
    throw std::invalid_argument("mesh_volume: a face index is out of range");
  // Tetrahedra against the centroid of the vertices rather than the origin: same sum for a closed mesh, less round-off
  // when the model sits far from the origin.
  const Eigen::Vector3d o = mesh.vertex_count() > 0 ? Eigen::Vector3d(mesh.vertices.colwise().mean().transpose())
                                                    : Eigen::Vector3d::Zero();
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose() - o;
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose() - o;
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose() - o;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double compactness(double bounding_volume, const TriangleMesh& mesh) {
  const double volume = std::abs(mesh_volume(mesh));
  if (volume == 0.0) throw std::invalid_argument("compactness: the mesh encloses no volume (open or flat?)");
  return bounding_volume / volume;
}

}  // namespace clothcd::geometry
