#pragma once
// Exact and near touches with decimal (non-power-of-two) coordinates, labelled by the exact rational reference: the
// cases where a filter's rounding-error bound is all that stands between a real contact and a culled pair.
#include <vector>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::test {

/// How a decimal touch query was built.
enum class TouchFamily {
  AtEnd,     ///< The primitives meet at t = 1 (vertex on the face, an edge through the other edge), approaching;
             ///< also vertices onto wide faces with exact normals and onto faces on the plane x + y + z = s.
  AtStart,   ///< An AtEnd query run backwards: the primitives meet at t = 0 and move apart.
  Interior,  ///< Contact at an interior time: an AtEnd motion prolonged, or a point sliding along an axis exactly
             ///< through a corner of the other primitive.
  Coplanar,  ///< All eight points on one axis-aligned plane at a decimal offset (z = c exactly).
  Nudged,    ///< An exact touch with one coordinate moved by one to three units in the last place.
};

/// Number of families (for per-family tallies).
inline constexpr int kTouchFamilies = 5;

/// One query of the family with the exact reference's verdict on its doubles.
struct LabelledTouch {
  ccd::CcdQuery query;        ///< The pair.
  bool collides = false;      ///< exact_collision_reference(query).
  TouchFamily family{};       ///< How it was built.
  int exponent = 0;           ///< Feature size 10^exponent.
};

/// A vertex-face query whose vertex ends within `thickness` of the face: the exact rational distance at t = 1 is
/// <= thickness and its foot lies inside the triangle, so the pair collides at that thickness.
struct ThickTouch {
  ccd::CcdQuery query;  ///< The pair.
  double thickness;     ///< The thickness it comes within at t = 1 (exactly, in rationals).
  int exponent = 0;     ///< Feature size 10^exponent.
};

/// The labelled thickness-0 set: features of size 10^-3 ... 10^3 on decimal grids (five significant digits of the
/// feature size), placed at the origin and at offsets of 2.7 and -1300 feature sizes. Seeded; built once per process.
[[nodiscard]] const std::vector<LabelledTouch>& decimal_touches();

/// The thickness set, same grids (only the queries the exact distance proves to collide).
[[nodiscard]] const std::vector<ThickTouch>& decimal_thick_touches();

/// The thicknesses the thickness-0 collisions are also checked at, for features of size 10^exponent.
[[nodiscard]] std::vector<double> touch_thicknesses(int exponent);

}  // namespace clothcd::test
