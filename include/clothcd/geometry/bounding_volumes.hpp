#pragma once
/// @file
/// Bounding volume types: axis-aligned box, sphere, oriented box. Builders live in their own headers.

#include <Eigen/Dense>
#include <limits>

namespace clothcd::geometry {

/// Axis-aligned bounding box; empty when min > max in any coordinate (the default).
struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());   ///< Lower corner.
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());  ///< Upper corner.

  /// Grows the box to contain point `p`.
  void expand(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  /// Grows the box to contain box `other`.
  void expand(const Aabb& other) {
    min = min.cwiseMin(other.min);
    max = max.cwiseMax(other.max);
  }
  /// Grows the box by `margin` on every side.
  void inflate(double margin) {
    min.array() -= margin;
    max.array() += margin;
  }
  /// True when the closed boxes share at least one point.
  [[nodiscard]] bool overlaps(const Aabb& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  /// True when `p` lies in the closed box.
  [[nodiscard]] bool contains(const Eigen::Vector3d& p) const {
    return (min.array() <= p.array()).all() && (p.array() <= max.array()).all();
  }
  /// Volume (0 for an empty or flat box).
  [[nodiscard]] double volume() const { return (max - min).cwiseMax(0.0).prod(); }
};

/// Bounding sphere.
struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< Centre.
  double radius = -1.0;                              ///< Radius; negative means empty.

  /// True when the closed spheres share at least one point.
  [[nodiscard]] bool overlaps(const Sphere& other) const {
    const double r = radius + other.radius;
    return radius >= 0 && other.radius >= 0 && (center - other.center).squaredNorm() <= r * r;
  }
  /// True when `p` lies in the closed sphere.
  [[nodiscard]] bool contains(const Eigen::Vector3d& p) const {
    return (p - center).squaredNorm() <= radius * radius;
  }
};

/// Oriented bounding box: centre + half extents along three orthonormal axes (the columns of `axes`).
struct Obb {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();        ///< Centre.
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();      ///< Columns: unit axes, right-handed.
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();  ///< Half side lengths along each axis.

  /// Volume 8 * hx * hy * hz.
  [[nodiscard]] double volume() const { return 8.0 * half_extents.prod(); }
  /// True when `p` lies in the closed box, up to `tolerance` along each axis.
  [[nodiscard]] bool contains(const Eigen::Vector3d& p, double tolerance = 0.0) const {
    return ((axes.transpose() * (p - center)).cwiseAbs() - half_extents).maxCoeff() <= tolerance;
  }
};

}  // namespace clothcd::geometry
