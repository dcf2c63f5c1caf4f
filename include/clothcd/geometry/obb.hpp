#pragma once
/// @file
/// Oriented bounding boxes: vertex PCA, the paper's fast adaptive OBB (Jin et al. eqs. 11-18), the same on a
/// QEM-simplified model grown to bound the original, and a tight reference from the convex hull.

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "clothcd/geometry/bounding_volumes.hpp"
#include "clothcd/geometry/support_points.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// How compute_obb chooses the box axes. Every method then takes the extents from the projections of every vertex it
/// was given, so each box contains all of them.
enum class ObbMethod {
  Covariance,              ///< (a) traditional OBB: axes are the eigenvectors of the vertex covariance about the vertex mean.
  FastAdaptive,            ///< (b) the paper's fast adaptive OBB: area-weighted centre, slab extremes, covariance of their triangles.
  FastAdaptiveSimplified,  ///< (c) (b) on the QEM-simplified model, grown to contain every original vertex.
  Tight                    ///< Reference: best box over the convex hull's face normals and edge directions (see compute_obb).
};

/// Options of compute_obb and SimplifiedObb.
struct ObbSettings {
  int slabs = 16;               ///< (b), (c): slabs per axis (s of eq. 15); the extremes of each slab are kept.
  double simplify_ratio = 0.1;  ///< (c): fraction of the faces the simplified model keeps (0.1 = the paper's 90% simplified).
  /// (b), (c): after the covariance axes, keep each axis in turn and re-choose the other two as the minimum-area
  /// rectangle of the slab extremes S' projected on its orthogonal plane (two rounds, the smallest box wins). An addition
  /// to the paper's method; false gives eqs. 11-18 exactly.
  bool refine_axes = true;
};

/// Reusable buffers of the fast adaptive OBB (so per-step rebuilds allocate nothing once warm).
struct ObbScratch {
  std::vector<char> keep;                ///< #V flags of the slab extremes S'.
  std::vector<int> kept_index;           ///< The rows of S' (distinct).
  std::vector<Eigen::Vector3d> kept;     ///< The points of S'.
  std::vector<Eigen::Vector2d> plane;    ///< S' projected on a plane.
  std::vector<Eigen::Vector2d> hull;     ///< Its 2-D convex hull.
  std::vector<int> kept_faces;           ///< The triangles touching S' (SimplifiedObb only).
};

/// The box of `mesh` (vertices #V x 3, faces #F x 3) by `method`; axes right-handed, half extents >= 0.
/// Tight: for every hull face normal and every hull edge direction taken as one axis, the minimum-area rectangle of the
/// hull projected on the orthogonal plane (rotating calipers) gives the other two; the smallest of these boxes is kept.
/// It is the exact optimum whenever the optimal box has a face flush with a hull face, and an upper bound otherwise.
/// Throws std::invalid_argument for an empty mesh or non-finite coordinates.
[[nodiscard]] Obb compute_obb(const TriangleMesh& mesh, ObbMethod method, const ObbSettings& settings = {});

/// The box with the given `axes` (columns, orthonormal) that tightly contains every row of `points` (#V x 3).
[[nodiscard]] Obb fit_obb_to_axes(const Vertices& points, const Eigen::Matrix3d& axes);

/// Grows `box` (axes kept) so that it contains every row of `points` (#V x 3), moving its centre as needed.
void grow_obb(Obb& box, const Vertices& points);

/// (c) for a moving obstacle: simplifies the model ONCE, then rebuilds the box every step in O(simplified + hull) time.
/// The box of update() takes its axes from the fast adaptive OBB of the simplified model at `pose` and its extents from
/// the projections of the original model's convex-hull vertices at `pose`; because a rigid (indeed any affine) map sends
/// the hull of the points to the hull of the mapped points, the box contains every original vertex at that pose.
/// Per update only the simplified model is moved: the centre of eqs. 11-14 is moved from rest, the triangles touching S'
/// bring their covariance moments precomputed at rest (turned by the pose), and each extent is an exact support query
/// over the hull vertices at rest along the axis turned back by the pose (SupportPoints: most hull vertices are skipped
/// by sphere bounds, none wrongly).
/// Threads: update() reuses the object's buffers, so one object belongs to one thread at a time; separate objects
/// may run in parallel.
class SimplifiedObb {
 public:
  /// Simplifies `original` to `settings.simplify_ratio` of its faces (QEM) and records its convex-hull vertices.
  /// Throws std::invalid_argument for an empty mesh or non-finite coordinates.
  explicit SimplifiedObb(const TriangleMesh& original, const ObbSettings& settings = {});

  /// The box of the model moved by `pose` (rest pose = identity). Allocates nothing after the first call. Throws
  /// std::invalid_argument for a non-finite pose.
  [[nodiscard]] Obb update(const Eigen::Isometry3d& pose);

  /// The box for a model whose vertices are now `original_vertices` (same #V as the original, any deformation): the
  /// axes come from the simplified model at rest moved by `pose`, the extents from every row of `original_vertices`.
  /// Throws std::invalid_argument for another vertex count or a non-finite coordinate or pose.
  [[nodiscard]] Obb update(const Eigen::Isometry3d& pose, const Vertices& original_vertices);

  /// The simplified model at rest.
  [[nodiscard]] const TriangleMesh& simplified() const { return simplified_; }
  /// Rows of the original vertices on its convex hull (what update() grows the box by).
  [[nodiscard]] const std::vector<int>& hull_vertex_indices() const { return hull_indices_; }

 private:
  TriangleMesh simplified_;
  Eigen::Index original_vertex_count_ = 0;
  std::vector<int> hull_indices_;
  SupportPoints hull_support_;  // original hull vertices at rest
  Eigen::Vector3d rest_centre_ = Eigen::Vector3d::Zero();  // eqs. 11-14 on the simplified model at rest
  std::vector<int> face_begin_, face_list_;  // simplified model: faces of vertex i in face_list_[face_begin_[i] ..)
  // Simplified model at rest, per face: its corners' moments about rest_centre_ (sum of p - c, then the upper triangle
  // of the sum of (p - c)(p - c)^T: xx, xy, xz, yy, yz, zz).
  std::vector<std::array<double, 9>> face_moments_;
  ObbSettings settings_;
  TriangleMesh moved_;  // scratch: simplified model at the current pose
  ObbScratch scratch_;
};

}  // namespace clothcd::geometry
