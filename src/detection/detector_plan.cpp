// A detector's settings turned into its parts' settings (see detector_plan.hpp).
#include "detector_plan.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace clothcd::detail {
namespace {

const DetectorSettings& checked(const DetectorSettings& settings) {
  if (!(settings.thickness >= 0.0) || !std::isfinite(settings.thickness)) {
    throw std::invalid_argument("collision detector: the thickness must be finite and >= 0");
  }
  if (settings.max_leaf_faces < 1) throw std::invalid_argument("collision detector: max_leaf_faces must be >= 1");
  if (settings.block_pairs < 1 || settings.block_pairs > kMaxBlockPairs) {
    throw std::invalid_argument("collision detector: block_pairs must be between 1 and " +
                                std::to_string(kMaxBlockPairs));
  }
  if (settings.max_collisions < 1 || settings.max_collisions > kLargestCollisionBudget) {
    throw std::invalid_argument("collision detector: max_collisions must be between 1 and " +
                                std::to_string(kLargestCollisionBudget));
  }
  if (settings.culling == CullingMode::Network && !settings.culler) {
    throw std::invalid_argument("collision detector: Network culling needs DetectorSettings::culler (e.g. "
                                "learning::load_network_culler)");
  }
  return settings;
}

ccd::CcdFilter ccd_filter(CullingMode mode) {
  switch (mode) {
    case CullingMode::None: return ccd::CcdFilter::None;
    case CullingMode::NonPenetration: return ccd::CcdFilter::NonPenetration;
    case CullingMode::Projection: return ccd::CcdFilter::Projection;
    case CullingMode::Filters: return ccd::CcdFilter::Combined;
    case CullingMode::Network: return ccd::CcdFilter::Combined;
  }
  throw std::invalid_argument("collision detector: unknown culling mode");
}

// The node volumes of a hierarchy kind: the cloth's (its self-collision search descends on boxes, so an AABB-OBB
// detector gives the cloth boxes) and the obstacles'.
struct HierarchyVolumes {
  broadphase::VolumeKind cloth;
  broadphase::VolumeKind obstacle;
};

HierarchyVolumes hierarchy_volumes(HierarchyKind hierarchy) {
  switch (hierarchy) {
    case HierarchyKind::SphereRootAabb: return {broadphase::VolumeKind::Sphere, broadphase::VolumeKind::Sphere};
    case HierarchyKind::Aabb: return {broadphase::VolumeKind::Aabb, broadphase::VolumeKind::Aabb};
    case HierarchyKind::AabbObb: return {broadphase::VolumeKind::Aabb, broadphase::VolumeKind::Obb};
  }
  throw std::invalid_argument("collision detector: unknown hierarchy kind");
}

}  // namespace

DetectorPlan::DetectorPlan(const DetectorSettings& detector_settings) : settings(checked(detector_settings)) {
  if (settings.culling == CullingMode::Network) culler = settings.culler;
  pair_tests.filter = ccd_filter(settings.culling);
  pair_tests.ccd = ccd::CcdSettings{settings.thickness, settings.decide_exactly};
  pair_tests.projection = ccd::ProjectionFilterOptions{settings.projection_normals};
  pair_tests.culler = culler.get();

  const HierarchyVolumes volumes = hierarchy_volumes(settings.hierarchy);
  cloth_hierarchy.volume = volumes.cloth;
  cloth_hierarchy.max_leaf_faces = settings.max_leaf_faces;
  cloth_hierarchy.rebuild_ratio = settings.rebuild_ratio;
  cloth_hierarchy.parallel = settings.parallel;
  obstacle_volume = volumes.obstacle;

  traversal.parallel = settings.parallel;
  traversal.chunk_pairs = static_cast<std::size_t>(settings.block_pairs);
}

}  // namespace clothcd::detail
