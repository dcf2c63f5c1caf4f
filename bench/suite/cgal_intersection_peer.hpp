#pragma once
/// @file
/// CGAL's self-intersection tests as the state benchmark runs them: Polygon_mesh_processing::self_intersections and
/// does_self_intersect on a Surface_mesh of the mesh, with exact predicates (Exact_predicates_inexact_constructions
/// kernel), sequential or parallel.

#include <array>
#include <memory>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::bench {

/// A mesh held as CGAL's Surface_mesh, its faces in the mesh's order.
class CgalMesh {
 public:
  /// Builds the Surface_mesh of `mesh` at `positions` (#V x 3). `refused` counts the faces Surface_mesh cannot hold
  /// (a non-manifold vertex or edge); CGAL's answers are only comparable when it is 0.
  CgalMesh(const Faces& faces, const Vertices& positions);
  ~CgalMesh();
  CgalMesh(const CgalMesh&) = delete;             ///< Not copyable.
  CgalMesh& operator=(const CgalMesh&) = delete;  ///< Not copyable.

  /// Faces Surface_mesh refused.
  [[nodiscard]] long refused() const { return refused_; }

  /// Every intersecting face pair (face indices of the mesh, smaller first), sorted; `parallel` runs CGAL's
  /// Parallel_tag (its TBB threads, as many as tbb::global_control allows), else Sequential_tag.
  [[nodiscard]] std::vector<std::array<int, 2>> self_intersections(bool parallel) const;

  /// does_self_intersect, sequential.
  [[nodiscard]] bool does_self_intersect() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  long refused_ = 0;
};

}  // namespace clothcd::bench
