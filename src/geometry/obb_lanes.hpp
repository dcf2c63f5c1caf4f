// The wide kernels of obb.cpp (the corner moments' sums, the rows moved by a pose), written once on the vector layer
// (support/simd.hpp) and compiled there for AVX2 by support/simd_versions.hpp; obb.cpp's own scalar code beside them
// is the baseline. No include guard and no includes of its own, on purpose.

// sum_moments four entries at a time: every entry summed in the same order.
CLOTHCD_SIMD_ENTRY FaceMoments sum_moments(const FaceMoments* moments, const int* faces, size_t count) {
  lanes::Doubles low = lanes::splat(0.0), high = low;
  double last = 0.0;
  for (size_t j = 0; j < count; ++j) {
    const double* m = moments[faces[j]].data();
    low = low + lanes::load(m);
    high = high + lanes::load(m + 4);
    last += m[8];
  }
  FaceMoments total;
  lanes::store(total.data(), low);
  lanes::store(total.data() + 4, high);
  total[8] = last;
  return total;
}

// Row p moved: the three coordinates in one register (the fourth lane unused), with move_rows's products and sums.
[[gnu::always_inline]] inline lanes::Doubles moved_row(const double* p,
                                                                          const lanes::Doubles column[3],
                                                                          lanes::Doubles shift) {
  return (column[0] * lanes::splat(p[0]) + (column[1] * lanes::splat(p[1]) + column[2] * lanes::splat(p[2]))) + shift;
}

CLOTHCD_SIMD_ENTRY void move_rows(const double* from, Eigen::Index rows, const Eigen::Matrix3d& r,
                                      const Eigen::Vector3d& t, double* to) {
  if (rows == 0) return;
  const lanes::Doubles column[3] = {lanes::make(r(0, 0), r(1, 0), r(2, 0), 0.0), lanes::make(r(0, 1), r(1, 1), r(2, 1), 0.0),
                                       lanes::make(r(0, 2), r(1, 2), r(2, 2), 0.0)};
  const lanes::Doubles shift = lanes::make(t[0], t[1], t[2], 0.0);
  // Four doubles stored per row: the fourth lands on the next row's x, which that row then overwrites.
  for (Eigen::Index i = 0; i + 1 < rows; ++i, from += 3, to += 3) lanes::store(to, moved_row(from, column, shift));
  lanes::store3(to, moved_row(from, column, shift));
}
