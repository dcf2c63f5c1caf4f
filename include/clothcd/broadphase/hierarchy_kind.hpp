#pragma once
/// @file
/// The kinds of bounding volume hierarchy the broad phase offers (the paper's Table 5 columns).

namespace clothcd {

/// Which bounding volume hierarchy finds candidate pairs.
enum class HierarchyKind {
  SphereRootAabb,  ///< Sphere BVH whose root also carries an AABB (the paper's root-node double bounding box).
  Aabb,            ///< Plain AABB BVH.
  AabbObb,         ///< AABBs on the cloth side, OBBs on the obstacle side.
};

}  // namespace clothcd
