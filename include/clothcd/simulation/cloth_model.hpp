#pragma once
/// @file
/// The mass-spring cloth: settings (shared, immutable), the model built from a triangle mesh (springs and masses) and
/// the running state (positions and velocities), kept apart as in Jolt's SoftBodySharedSettings / SoftBody split.

#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::simulation {

/// What a spring resists.
enum class SpringKind : unsigned char {
  Structural,  ///< Stretch along the weave: the mesh edges that are not quad diagonals.
  Shear,       ///< In-plane shear: both diagonals of each quad.
  Bending,     ///< Out-of-plane bending: skip-one springs along straight lines of structural edges.
};

/// Material and force settings of the cloth (SI units: metres, kilograms, seconds).
struct ClothSettings {
  double density = 0.2;                ///< Area density, kg / m^2 (cotton is about 0.1 - 0.3).
  double structural_stiffness = 800;   ///< Spring constant of structural springs, N / m.
  double shear_stiffness = 200;        ///< Spring constant of shear springs, N / m.
  double bending_stiffness = 5;        ///< Spring constant of bending springs, N / m.
  double spring_damping = 0.5;         ///< Damping along each spring, N s / m.
  double air_damping = 0.02;           ///< Velocity damping per unit mass, 1 / s.
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  ///< Acceleration of gravity, m / s^2.
};

/// One spring between cloth vertices `a` < `b`.
struct Spring {
  int a = 0;                                  ///< First vertex.
  int b = 0;                                  ///< Second vertex.
  double rest_length = 0;                     ///< Length at rest, m.
  SpringKind kind = SpringKind::Structural;   ///< What the spring resists.
};

/// The cloth's fixed data: topology, springs and per-vertex masses.
struct ClothModel {
  TriangleMesh rest;              ///< The cloth mesh at rest (its positions are the initial state).
  std::vector<Spring> springs;    ///< Every spring, structural first, then shear, then bending.
  std::vector<double> masses;     ///< #V masses, kg (one third of each adjacent triangle's mass).
  std::vector<char> pinned;       ///< #V flags: 1 for a vertex held in place (infinite mass).
  ClothSettings settings;         ///< The settings the model was built with.

  /// Number of cloth vertices.
  [[nodiscard]] int vertex_count() const { return static_cast<int>(rest.vertices.rows()); }
  /// Inverse mass of vertex `v`: 0 when pinned.
  [[nodiscard]] double inverse_mass(int v) const { return pinned[v] ? 0.0 : 1.0 / masses[v]; }
};

/// The running state: positions and velocities, #V x 3 each.
struct ClothState {
  Vertices positions;   ///< #V x 3 positions, m.
  Vertices velocities;  ///< #V x 3 velocities, m / s.
};

/// Builds springs and masses from `mesh` (validated: finite, indices in range, at least one face).
/// `pinned_vertices` lists vertex indices held in place. Throws std::invalid_argument on a bad mesh, a negative or
/// non-finite setting, or a pinned index out of range.
[[nodiscard]] ClothModel build_cloth_model(const TriangleMesh& mesh, const ClothSettings& settings = {},
                                           const std::vector<int>& pinned_vertices = {});

/// The state at rest: the model's rest positions, zero velocities.
[[nodiscard]] ClothState rest_state(const ClothModel& model);

/// Counts of each spring kind in `model`: index by static_cast<int>(SpringKind).
[[nodiscard]] std::vector<int> count_springs(const ClothModel& model);

}  // namespace clothcd::simulation
