#pragma once
/// @file
/// A small software rasterizer: perspective camera, z-buffer, flat two-sided Lambert shading. Enough to look at frames.

#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"
#include "clothcd/render/image.hpp"

namespace clothcd::render {

/// A pinhole camera.
struct Camera {
  Eigen::Vector3d eye{2.0, 1.8, 2.6};       ///< Position.
  Eigen::Vector3d target{0.0, 0.4, 0.0};    ///< Point looked at.
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();  ///< Up direction.
  double fov_degrees = 40;                  ///< Vertical field of view.
};

/// One mesh to draw and its colour (components in [0, 1]).
struct RenderItem {
  const TriangleMesh* mesh = nullptr;                   ///< The mesh (not owned).
  Eigen::Vector3d color{0.8, 0.8, 0.8};                 ///< Base colour.
};

/// Image size and background.
struct RenderSettings {
  int width = 640;                                      ///< Pixels.
  int height = 480;                                     ///< Pixels.
  Eigen::Vector3d background{0.96, 0.96, 0.98};         ///< Background colour in [0, 1].
  Eigen::Vector3d light_direction{0.4, 1.0, 0.6};       ///< Direction towards the light (need not be unit).
};

/// Renders `items` seen from `camera`. Throws std::invalid_argument on a null mesh or a non-positive size.
[[nodiscard]] Image render(const std::vector<RenderItem>& items, const Camera& camera,
                           const RenderSettings& settings = {});

/// A camera that frames the axis-aligned box [lo, hi] from the front, above and to the right.
[[nodiscard]] Camera frame_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace clothcd::render
