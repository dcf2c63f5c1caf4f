#pragma once
// Private: the 2D test shared by the exact CCD stages (the GMP reference and the expansion tier): does a projected
// triangle W[a] W[b] W[c] contain the origin, decided from exact signs alone.
#include <array>

namespace clothcd::ccd::detail {

/// True when the origin lies in the (closed, possibly degenerate) triangle of points a, b, c of a projection, given
/// the exact signs of the 2D cross products W[a] x W[b], W[b] x W[c], W[c] x W[a] and `dot_sign(i, j)`, the exact
/// sign of the 2D dot product W[i] . W[j]. Mixed cross signs: outside. Some non-zero sign, all agreeing: inside.
/// All zero (the points lie on one line through the origin): inside iff two of them (or one with itself, a point at
/// the origin) are not strictly on the same side.
template <class DotSign>
[[nodiscard]] bool triangle_contains_origin_by_signs(const std::array<int, 3>& cross, const std::array<int, 3>& ids,
                                                     const DotSign& dot_sign) {
  const bool has_positive = cross[0] > 0 || cross[1] > 0 || cross[2] > 0;
  const bool has_negative = cross[0] < 0 || cross[1] < 0 || cross[2] < 0;
  if (has_positive && has_negative) return false;
  if (has_positive || has_negative) return true;
  for (const int i : ids)
    for (const int j : ids)
      if (dot_sign(i, j) <= 0) return true;
  return false;
}

}  // namespace clothcd::ccd::detail
