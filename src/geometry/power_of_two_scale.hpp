#pragma once
// Private: the power of two that brings a point set's largest coordinate magnitude near 1. Scaling by it is exact (no
// rounding, as long as nothing becomes subnormal), so an algorithm that squares or multiplies coordinates can run on
// the scaled points and its lengths be scaled back, where on the raw points its products would overflow (from about
// 1e150) or underflow (below about 1e-150).
#include <cmath>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::geometry::detail {

/// e with 2^e <= the largest |coordinate| < 2^(e+1) when that is outside [2^-60, 2^61), else 0 (no scaling needed).
inline int far_scale_exponent(const Vertices& points) {
  const double largest = points.size() > 0 ? points.cwiseAbs().maxCoeff() : 0.0;
  if (!(largest > 0.0) || !std::isfinite(largest)) return 0;
  const int exponent = std::ilogb(largest);
  return exponent < -60 || exponent > 60 ? exponent : 0;
}

}  // namespace clothcd::geometry::detail
