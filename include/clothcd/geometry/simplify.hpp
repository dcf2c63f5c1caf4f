#pragma once
/// @file
/// Surface simplification by quadric error metrics (Garland & Heckbert 1997), as section 2.1 of Jin et al. uses it.

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// When simplify_qem stops and what it may contract. The first target reached stops it.
struct SimplifySettings {
  int target_faces = -1;        ///< Stop at this many faces or fewer (ignored when < 0).
  double target_ratio = -1.0;   ///< Stop at this fraction of the input's faces, in (0, 1] (ignored when < 0).
  double max_error = -1.0;      ///< Stop before a contraction moving the surface more than this (model units, RMS of the
                                ///< quadric distance; ignored when < 0).
  double non_edge_threshold = 0.0;  ///< Also contract vertex pairs closer than this (model units) that share no edge,
                                    ///< joining separate parts (paper Fig. 3); 0 = edges only.
  double boundary_weight = 1000.0;  ///< Weight of the penalty planes that hold open boundaries in place.
  double min_normal_cos = 0.2;  ///< Reject a contraction turning any face normal by more than acos(this).
};

/// What simplify_qem produced.
struct SimplifyResult {
  TriangleMesh mesh;         ///< The simplified mesh (unused vertices removed, faces keep their orientation).
  int faces_before = 0;      ///< Faces of the input.
  int faces_after = 0;       ///< Faces of `mesh`.
  int contractions = 0;      ///< Vertex pairs contracted.
  double max_error = 0.0;    ///< Largest quadric error of an applied contraction, as a distance in model units.
  bool reached_target = false;  ///< False when no valid contraction was left before the face target.
};

/// Simplifies `mesh` by repeated contraction of the cheapest valid vertex pair (4-ary heap, lazy deletion by version
/// stamps). Positions are rescaled to unit extent internally. A contraction is rejected when it would flip or degenerate
/// a face, create a non-manifold edge, pinch two boundaries together, or duplicate a face. The new vertex minimises the
/// summed quadric (4x4 solve), else the best point on the segment, else the best of the endpoints and midpoint.
/// Throws std::invalid_argument when no target is set, a target is out of range, or the mesh is invalid.
[[nodiscard]] SimplifyResult simplify_qem(const TriangleMesh& mesh, const SimplifySettings& settings);

}  // namespace clothcd::geometry
