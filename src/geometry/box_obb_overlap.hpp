#pragma once
/// @file
/// The overlap test of an axis-aligned box against an oriented box: the broad phase's AABB-OBB hierarchy pairs descend
/// on it. The box comes as its two corners, so that callers test their own box layout in place.

#include "clothcd/geometry/bounding_volumes.hpp"

namespace clothcd::geometry {

/// True unless one of the 15 candidate separating axes (Gottschalk et al. 1996: the box's three, the OBB's three and
/// their nine cross products) separates the closed box [box_min, box_max] from `obb`. Conservative: the projected
/// radii are widened slightly (1e-9 on every |rotation| entry) to absorb rounding, so volumes whose contents overlap
/// are never reported apart.
[[nodiscard]] bool box_obb_overlap(const double (&box_min)[3], const double (&box_max)[3], const Obb& obb);

}  // namespace clothcd::geometry
