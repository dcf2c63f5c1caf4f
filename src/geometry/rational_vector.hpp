#pragma once
/// @file
/// Three-dimensional vectors of GMP rationals and the few exact operations the pair distances' exact tier and
/// reference need (geometry/rational_pair_distance.hpp, geometry/exact_pair_distance.hpp). Doubles convert exactly.
/// The operators act on std::array, so callers name them with using-declarations (argument-dependent lookup looks in
/// namespace std only).
#include <gmpxx.h>

#include <Eigen/Dense>

#include <array>

namespace clothcd::geometry::rational {

/// A point or vector with exact rational coordinates.
using Vector = std::array<mpq_class, 3>;

/// The exact coordinates of a double point.
[[nodiscard]] Vector from_double(const Eigen::Vector3d& x);

/// a - b.
[[nodiscard]] Vector operator-(const Vector& a, const Vector& b);

/// a + b.
[[nodiscard]] Vector operator+(const Vector& a, const Vector& b);

/// s a.
[[nodiscard]] Vector operator*(const mpq_class& s, const Vector& a);

/// a . b.
[[nodiscard]] mpq_class dot(const Vector& a, const Vector& b);

/// a x b.
[[nodiscard]] Vector cross(const Vector& a, const Vector& b);

/// True when every coordinate is 0.
[[nodiscard]] bool is_zero(const Vector& a);

/// The square root of x >= 0 as a double, within one unit in the last place (2^-52 relative) in the normal range:
/// x is scaled by an even power of two into (1/4, 4) before it is rounded, so a square that no double can hold still
/// has its root.
[[nodiscard]] double square_root(const mpq_class& x);

/// a rounded to doubles and scaled to unit length (zero stays zero).
[[nodiscard]] Eigen::Vector3d unit_direction(const Vector& a);

}  // namespace clothcd::geometry::rational
