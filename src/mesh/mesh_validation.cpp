// Mesh validation at the boundary: everything past load_mesh may assume finite coordinates and valid indices.
#include "clothcd/mesh/mesh_validation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "clothcd/mesh/mesh_error.hpp"

namespace clothcd {

void validate_mesh(const TriangleMesh& mesh, const std::string& context) {
  if (mesh.face_count() == 0) throw MeshError(context, "the mesh has no faces");
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(mesh.vertices(v, c))) {
        throw MeshError(context, "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                                     std::to_string(mesh.vertices(v, c)) + ")");
      }
    }
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int index = mesh.faces(f, c);
      if (index < 0 || index >= mesh.vertex_count()) {
        throw MeshError(context, "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                                     ", outside [0, " + std::to_string(mesh.vertex_count()) + ")");
      }
    }
  }
}

bool is_degenerate_face(const TriangleMesh& mesh, Eigen::Index f) {
  if (f < 0 || f >= mesh.face_count()) throw std::out_of_range("is_degenerate_face: no face " + std::to_string(f));
  const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  const int n = static_cast<int>(mesh.vertex_count());
  if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n)
    throw std::out_of_range("is_degenerate_face: face " + std::to_string(f) + " has a vertex index out of range");
  if (a == b || b == c || a == c) return true;
  const Eigen::Vector3d pa = mesh.vertices.row(a), pb = mesh.vertices.row(b), pc = mesh.vertices.row(c);
  return (pb - pa).cross(pc - pa).squaredNorm() == 0.0;
}

int drop_degenerate_faces(TriangleMesh& mesh) {
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    if (!is_degenerate_face(mesh, f)) mesh.faces.row(kept++) = mesh.faces.row(f);
  }
  const int dropped = static_cast<int>(mesh.face_count() - kept);
  mesh.faces.conservativeResize(kept, 3);
  return dropped;
}

}  // namespace clothcd
