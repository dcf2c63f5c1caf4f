#pragma once
/// @file
/// Procedural meshes: square cloths (the paper's A, B, C and any N x M grid), UV spheres, boxes, a fish stand-in.

#include <Eigen/Dense>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// A flat rectangular grid of `columns` x `rows` vertices spanning `width` (x) by `depth` (z) at height y = 0, centred on
/// the origin; 2 (columns-1)(rows-1) triangles, normals +y. Throws std::invalid_argument if columns or rows < 2 or a size
/// is not positive and finite.
[[nodiscard]] TriangleMesh make_grid(int columns, int rows, double width = 1.0, double depth = 1.0);

/// The paper's square cloths: 'A' 20x20 vertices (722 triangles), 'B' 30x30 (1682), 'C' 50x50 (4802), of side `size`.
/// Throws std::invalid_argument for any other letter.
[[nodiscard]] TriangleMesh make_paper_cloth(char name, double size = 1.0);

/// A closed UV sphere of `radius` with `slices` >= 3 segments around and `stacks` >= 2 from pole to pole, outward normals.
[[nodiscard]] TriangleMesh make_uv_sphere(double radius = 1.0, int slices = 32, int stacks = 16);

/// A closed axis-aligned box centred at the origin with the given half extents, each face split in 2 triangles (12 in all).
[[nodiscard]] TriangleMesh make_box(const Eigen::Vector3d& half_extents = Eigen::Vector3d::Ones());

/// A closed, fish-like body: a spindle-shaped body along +x with a forked tail fin, about 2 units long. Used as the
/// stand-in for the paper's fish model, which no Debian package ships.
[[nodiscard]] TriangleMesh make_fish(int slices = 24, int stations = 32);

}  // namespace clothcd
