#pragma once
// Private: the slab extremes of Jin et al. eqs. 15-16 (the kept set S' of the fast adaptive OBB).

#include <Eigen/Core>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry::detail {

/// Values compared in each slab: the distance from the centre and the extremes in the two other coordinates.
inline constexpr int kSlabValues = 5;
/// The most slabs per axis (more are clamped to it).
inline constexpr int kMaxSlabs = 256;

/// Eqs. 15-16: each coordinate axis a of `points` (#V x 3) is cut into s = clamp(slabs, 1, kMaxSlabs) slabs of equal
/// width between the smallest and largest coordinate; in each slab the rows with the largest of the kSlabValues values
/// {|p - centre|^2, p[b], -p[b], p[c], -p[c]} (b, c the two other axes), the first such row on ties, are written to
/// rows[(a * s + slab) * kSlabValues + k] (-1 for an empty slab). `rows` must hold 3 * s * kSlabValues entries.
/// Without branches on the data where the CPU has AVX2 (x86-64, chosen at run time), else slab_extremes_reference.
void slab_extremes(const Vertices& points, const Eigen::Vector3d& centre, int slabs, int* rows);

/// The same rows by a plain scan with a branch per comparison: the reference slab_extremes is tested against.
void slab_extremes_reference(const Vertices& points, const Eigen::Vector3d& centre, int slabs, int* rows);

}  // namespace clothcd::geometry::detail
