// The wide kernel of slab_extremes.cpp (every slab's extreme points), written once on the vector layer (support/simd.hpp)
// and compiled in slab_extremes.cpp for AVX2 by support/simd_versions.hpp; the scalar code beside it there is the
// baseline. No include guard and no includes of its own, on purpose.

// Per slab: the running best of {p[b], p[c], -p[b], -p[c]} and of the distance from the centre (lanes 1 to 3 unused,
// never beaten), with their rows as doubles (exact) so that one comparison mask selects value and row together.
struct alignas(32) SlabBest {
  double extreme[4];
  double extreme_row[4];
  double far[4];
  double far_row[4];
};

// bounds() with a row in one register (the fourth lane unused); min(p, low) is exactly std::min(low, p), and so on.
inline void bounds_wide(const Vertices& points, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  low.setZero();
  high.setZero();
  if (points.rows() == 0) return;
  lanes::Doubles lo = lanes::load3(points.data()), hi = lo;
  for (Eigen::Index i = 1; i < points.rows(); ++i) {
    const lanes::Doubles p = lanes::load3(points.data() + 3 * i);
    lo = lanes::min(p, lo);
    hi = lanes::max(p, hi);
  }
  double l[4], h[4];
  lanes::store(l, lo);
  lanes::store(h, hi);
  low = Eigen::Vector3d(l[0], l[1], l[2]);
  high = Eigen::Vector3d(h[0], h[1], h[2]);
}

// Updates the running bests `best` and their rows `best_row` by `value` (row `row`): a strictly greater value
// replaces the running best and its row (so ties keep the first row); max(value, old) is value exactly where
// value > old.
[[gnu::always_inline]] inline void take_greater(double* best, double* best_row,
                                                                  lanes::Doubles value, lanes::Doubles row) {
  const lanes::Doubles old = lanes::load(best);
  lanes::store(best, lanes::max(value, old));
  lanes::store(best_row, lanes::select(value > old, row, lanes::load(best_row)));
}

// Updates `slab` (of axis a) by the point p (row `row`, distance `far` from the centre in lane 0, -infinity in the
// others).
[[gnu::always_inline]] inline void take_better(SlabBest& slab, const double* p, int a,
                                                                 lanes::Doubles far, lanes::Doubles row) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  take_greater(slab.extreme, slab.extreme_row, lanes::make(p[b], p[c], 0.0 - p[b], 0.0 - p[c]), row);
  take_greater(slab.far, slab.far_row, far, row);
}

// The running bests of every slab, updated point by point. The slab indices of a block of points are computed before
// the block's updates, so the updates' addresses are known early (else each load of a running best may wait for, or
// be replayed after, the stores of the point before, which often hit the same slab).
CLOTHCD_SIMD_ENTRY void slab_extremes(const Vertices& points, const Eigen::Vector3d& centre,
                                                        int slabs, int* rows) {
  Eigen::Vector3d low, high;
  bounds_wide(points, low, high);
  const Slabs cut(low, high, slabs);
  const int slab_count = 3 * cut.count;
  std::array<SlabBest, 3 * kMaxSlabs> best;
  const double never = -std::numeric_limits<double>::infinity();
  std::fill_n(best.begin(), slab_count, SlabBest{{never, never, never, never}, {-1, -1, -1, -1},
                                                 {never, never, never, never}, {-1, -1, -1, -1}});
  // Slab of each axis as in Slabs::of, for x, y, z at once (the fourth lane unused), offset to the axis's slabs.
  const lanes::Doubles lo = lanes::make(cut.lo[0], cut.lo[1], cut.lo[2], 0.0);
  const lanes::Doubles inv_width = lanes::make(cut.inv_width[0], cut.inv_width[1], cut.inv_width[2], 0.0);
  const simd::I32x4 last = {cut.count - 1, cut.count - 1, cut.count - 1, cut.count - 1};
  const simd::I32x4 first_of_axis = {0, cut.count, 2 * cut.count, 0};
  constexpr int kBlock = 64;
  alignas(16) std::array<int, 4 * kBlock> slab_of;
  const Eigen::Index n = points.rows();
  for (Eigen::Index start = 0; start < n; start += kBlock) {
    const int count = static_cast<int>(std::min<Eigen::Index>(kBlock, n - start));
    for (int j = 0; j < count; ++j) {
      const lanes::Doubles p = lanes::load3(points.data() + 3 * (start + j));
      const simd::I32x4 slab = lanes::truncate((p - lo) * inv_width);
      const simd::I32x4 axis_slab = (slab < last ? slab : last) + first_of_axis;
      std::memcpy(slab_of.data() + 4 * j, &axis_slab, sizeof axis_slab);
    }
    for (int j = 0; j < count; ++j) {
      const double* p = points.data() + 3 * (start + j);
      const lanes::Doubles far = lanes::make(squared_distance(p, centre), never, never, never);
      const lanes::Doubles row = lanes::splat(double(start + j));
      for (int a = 0; a < 3; ++a) take_better(best[size_t(slab_of[size_t(4 * j + a)])], p, a, far, row);
    }
  }
  for (int j = 0; j < slab_count; ++j) {
    const SlabBest& slab = best[size_t(j)];
    int* out = rows + j * kSlabValues;  // values {far, p[b], -p[b], p[c], -p[c]}
    out[0] = static_cast<int>(slab.far_row[0]);
    out[1] = static_cast<int>(slab.extreme_row[0]);
    out[2] = static_cast<int>(slab.extreme_row[2]);
    out[3] = static_cast<int>(slab.extreme_row[1]);
    out[4] = static_cast<int>(slab.extreme_row[3]);
  }
}

