#pragma once
/// @file
/// Rigid obstacles: a mesh at rest and a motion made of a constant translation and rotation per step.

#include <string>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::simulation {

/// A rigid motion repeated every step for the first `moving_steps` steps, then the obstacle stays where it is.
/// Pose after s steps: x = R(s angle) (x_rest - pivot) + pivot + s translation.
struct RigidMotion {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< Displacement per step, scene units.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();        ///< Rotation axis (need not be unit; zero means none).
  double angle = 0;                                       ///< Rotation per step about the axis, radians.
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();        ///< Point the rotation turns about, at rest.
  int moving_steps = 0;                                   ///< How many steps the motion lasts (0: static).
};

/// A rigid obstacle.
struct Obstacle {
  std::string name;     ///< Model name (for output files).
  TriangleMesh rest;    ///< Mesh in its pose at step 0.
  RigidMotion motion;   ///< Motion per step.

  /// True when the obstacle moves during step `step` (from pose `step` to pose `step + 1`).
  [[nodiscard]] bool moves_during(int step) const;
  /// The vertex positions (#V x 3) after `step` steps.
  [[nodiscard]] Vertices positions_at(int step) const;
  /// Maps a point `p` given in the pose after `step` steps to where the obstacle's motion carries it during that step
  /// (the point moves as if glued to the obstacle).
  [[nodiscard]] Eigen::Vector3d carry(const Eigen::Vector3d& p, int step) const;
};

/// Scales `mesh` uniformly so that its largest bounding-box extent is `size`, turns it so that axis `up` (0 = x,
/// 1 = y, 2 = z) points along +y, centres it over the origin in x and z and puts its lowest point at y = 0.
[[nodiscard]] TriangleMesh normalize_obstacle(const TriangleMesh& mesh, int up = 1, double size = 1.0);

}  // namespace clothcd::simulation
