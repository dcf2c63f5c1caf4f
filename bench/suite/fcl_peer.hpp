#pragma once
/// @file
/// FCL (the peer of the broad phase): triangle meshes as FCL AABB hierarchies, refitted per frame.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>

#include <memory>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::bench {

/// FCL's AABB bounding volume hierarchy over a triangle mesh.
using FclModel = fcl::BVHModel<fcl::AABBd>;

/// The rows of `v` as FCL points.
[[nodiscard]] std::vector<fcl::Vector3d> fcl_points(const Vertices& v);

/// An FCL hierarchy of `mesh`'s triangles at `positions`.
[[nodiscard]] std::shared_ptr<FclModel> fcl_model(const TriangleMesh& mesh, const Vertices& positions);

/// Refits `model` to `positions` (same vertex count as built) and collides it with `other` asking for every
/// contact (triangle pairs); returns the contact count.
std::size_t fcl_refit_and_collide(const std::shared_ptr<FclModel>& model, const std::vector<fcl::Vector3d>& positions,
                                  const std::shared_ptr<FclModel>& other);

}  // namespace clothcd::bench
