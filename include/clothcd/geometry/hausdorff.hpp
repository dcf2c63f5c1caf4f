#pragma once
/// @file
/// Two-sided sampled Hausdorff distance between two triangle meshes (as Metro measures it).

#include <cstdint>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry {

/// Sampling of measure_hausdorff.
struct HausdorffSettings {
  int samples = 200000;       ///< Random area-weighted surface samples per side, added to every vertex and face centroid.
  std::uint64_t seed = 1;     ///< Sampling seed (deterministic).
};

/// Distances between two surfaces, in model units.
struct HausdorffResult {
  double max = 0.0;   ///< Largest distance from a sample of either mesh to the other surface (two-sided Hausdorff).
  double mean = 0.0;  ///< Mean of the sample distances, over both sides.
  double a_to_b = 0.0;  ///< One-sided max from samples of `a` to surface `b`.
  double b_to_a = 0.0;  ///< One-sided max from samples of `b` to surface `a`.
};

/// Samples each surface (vertices, face centroids, and `samples` random points by area) and measures the distance of
/// every sample to the other surface exactly (closest point on triangles through a bounding volume hierarchy).
/// Throws std::invalid_argument when either mesh has no faces, a non-finite coordinate or a face index out of range.
[[nodiscard]] HausdorffResult measure_hausdorff(const TriangleMesh& a, const TriangleMesh& b,
                                                const HausdorffSettings& settings = {});

/// The two-sided sampled Hausdorff distance measure_hausdorff(a, b, settings).max.
[[nodiscard]] double hausdorff_distance(const TriangleMesh& a, const TriangleMesh& b,
                                        const HausdorffSettings& settings = {});

}  // namespace clothcd::geometry
