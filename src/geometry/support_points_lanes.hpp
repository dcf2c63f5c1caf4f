// The wide kernel of support_points.cpp (the scan of all points), written once on the vector layer (support/simd.hpp)
// and compiled in support_points.cpp for AVX2 by support/simd_versions.hpp; the scalar code beside it there is the
// baseline. No include guard and no includes of its own, on purpose.

// {min, max} of x[i] dx + y[i] dy + z[i] dz over i < count (a multiple of 4; x, y, z the rows of `count` values at
// `coordinates`), four points at a time, each product summed in the order of Eigen's dot product of the point with the
// direction, so the values are those of a scan.
CLOTHCD_SIMD_ENTRY std::pair<double, double> scan_min_max(const double* coordinates, size_t count,
                                                         const Eigen::Vector3d& direction) {
  const double* x = coordinates;
  const double* y = coordinates + count;
  const double* z = coordinates + 2 * count;
  const lanes::Doubles dx = lanes::splat(direction.x()), dy = lanes::splat(direction.y()),
                dz = lanes::splat(direction.z());
  lanes::Doubles lo = lanes::splat(std::numeric_limits<double>::infinity());
  lanes::Doubles hi = lanes::splat(-std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < count; i += 4) {
    const lanes::Doubles dot = (lanes::load(x + i) * dx + lanes::load(y + i) * dy) + lanes::load(z + i) * dz;
    lo = lanes::min(lo, dot);
    hi = lanes::max(hi, dot);
  }
  double low[4], high[4];
  lanes::store(low, lo);
  lanes::store(high, hi);
  return {std::min(std::min(low[0], low[1]), std::min(low[2], low[3])),
          std::max(std::max(high[0], high[1]), std::max(high[2], high[3]))};
}

