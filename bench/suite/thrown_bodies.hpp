#pragma once
/// @file
/// Generated large-motion steps for the scale benchmark: bodies (UV spheres, cloth sheets, fish) on a lattice, each
/// thrown through its neighbours, so that their swept triangles overlap by the million. Every scene is one multi-body
/// mesh at the start and the end of the step, as `clothcd detect T0 T1` sees it, and depends only on its parameters
/// and seed (the same bits on every machine).

#include <cstdint>
#include <string>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::bench {

/// The parameters of one generated scene.
struct ThrownBodiesSpec {
  std::string name;            ///< Scene name in the report, e.g. "thrown-16".
  int bodies = 8;              ///< Number of bodies (>= 1); kinds repeat sphere, sheet, sphere, fish.
  int resolution = 16;         ///< Segments around a sphere or fish, vertices along a sheet's side (>= 4).
  double throw_distance = 1.0; ///< How far a body travels over the step at most, in lattice cells (> 0).
  std::uint64_t seed = 1;      ///< Seed of the placement, sizes, rotations and throws.
};

/// One step of a generated scene: every body in one mesh, at the start and at the end of the step.
struct ThrownBodiesStep {
  TriangleMesh start;  ///< All bodies' triangles and their start positions.
  Vertices end;        ///< End positions (same rows as start.vertices).
};

/// Builds the scene `spec` describes: body i is about one unit across, sits near cell i of a cubic lattice of cells
/// 1.5 units apart (filled x first, then y, then z), is rotated at random, and over the step moves in a random
/// direction by 70-100% of `throw_distance` cells while turning by up to half a radian. Throws std::invalid_argument
/// on parameters out of range.
[[nodiscard]] ThrownBodiesStep make_thrown_bodies(const ThrownBodiesSpec& spec);

}  // namespace clothcd::bench
