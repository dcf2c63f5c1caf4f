// CGAL's self-intersection tests on a Surface_mesh (see cgal_intersection_peer.hpp).
// The bench links TBB, so CGAL's Parallel_tag may use it (CGAL only reads this macro).
#ifndef CGAL_LINKED_WITH_TBB
#define CGAL_LINKED_WITH_TBB
#endif
#include "cgal_intersection_peer.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <utility>

namespace clothcd::bench {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using FaceIndex = SurfaceMesh::Face_index;
namespace pmp = CGAL::Polygon_mesh_processing;
}  // namespace

struct CgalMesh::Impl {
  SurfaceMesh mesh;
  std::vector<int> face_of;  // mesh face index of each Surface_mesh face
};

CgalMesh::CgalMesh(const Faces& faces, const Vertices& positions) : impl_(std::make_unique<Impl>()) {
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(static_cast<std::size_t>(positions.rows()));
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    vertices.push_back(impl_->mesh.add_vertex({positions(v, 0), positions(v, 1), positions(v, 2)}));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const FaceIndex added = impl_->mesh.add_face(vertices[faces(f, 0)], vertices[faces(f, 1)], vertices[faces(f, 2)]);
    if (added == SurfaceMesh::null_face()) {
      ++refused_;
      continue;
    }
    impl_->face_of.push_back(static_cast<int>(f));
  }
}

CgalMesh::~CgalMesh() = default;

std::vector<std::array<int, 2>> CgalMesh::self_intersections(bool parallel) const {
  std::vector<std::pair<FaceIndex, FaceIndex>> found;
  if (parallel)
    pmp::self_intersections<CGAL::Parallel_tag>(impl_->mesh, std::back_inserter(found));
  else
    pmp::self_intersections<CGAL::Sequential_tag>(impl_->mesh, std::back_inserter(found));
  std::vector<std::array<int, 2>> pairs;
  pairs.reserve(found.size());
  for (const auto& [a, b] : found) {
    const int fa = impl_->face_of[a.idx()], fb = impl_->face_of[b.idx()];
    pairs.push_back({std::min(fa, fb), std::max(fa, fb)});
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

bool CgalMesh::does_self_intersect() const {
  return pmp::does_self_intersect<CGAL::Sequential_tag>(impl_->mesh);
}

}  // namespace clothcd::bench
