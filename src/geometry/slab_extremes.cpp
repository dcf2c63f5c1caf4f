// Slab extremes of the fast adaptive OBB (Jin et al. eqs. 15-16). Which row wins a slab is data-dependent, so the
// reference's branches are often mispredicted; the fast version (x86-64 with AVX2, chosen at run time) updates each
// slab's running bests with comparison masks instead, four values at a time.
#include "slab_extremes.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

#include "clothcd/simd_level.hpp"
#include "support/simd.hpp"


namespace clothcd::geometry::detail {
namespace {

// The slab count and, per axis, the smallest coordinate and slabs / width (0 when the axis is flat: one slab).
struct Slabs {
  int count;
  Eigen::Vector3d lo, inv_width;

  // From the smallest and largest coordinates.
  Slabs(const Eigen::Vector3d& low, const Eigen::Vector3d& high, int slabs)
      : count(std::clamp(slabs, 1, kMaxSlabs)), lo(low) {
    for (int a = 0; a < 3; ++a) inv_width[a] = high[a] > low[a] ? count / (high[a] - low[a]) : 0.0;
  }

  [[nodiscard]] int of(const double* p, int a) const {
    return std::min(count - 1, static_cast<int>((p[a] - lo[a]) * inv_width[a]));
  }
};

// The smallest and largest coordinates of `points` (zero when there are none). A plain loop over the rows: Eigen's
// column-wise reductions of a row-major matrix are several times slower.
void bounds(const Vertices& points, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  low.setZero();
  high.setZero();
  if (points.rows() > 0) low = high = Eigen::Vector3d(points(0, 0), points(0, 1), points(0, 2));
  for (Eigen::Index i = 1; i < points.rows(); ++i) {
    const double* p = points.data() + 3 * i;
    for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
  }
}

double squared_distance(const double* p, const Eigen::Vector3d& centre) {
  return (Eigen::Vector3d(p[0], p[1], p[2]) - centre).squaredNorm();
}

#if defined(CLOTHCD_SIMD_X86)

// Per slab: the running best of {p[b], p[c], -p[b], -p[c]} and of the distance from the centre (lanes 1 to 3 unused,
// never beaten), with their rows as doubles (exact) so that one comparison mask selects value and row together.
struct alignas(32) SlabBest {
  double extreme[4];
  double extreme_row[4];
  double far[4];
  double far_row[4];
};

// bounds() with a row in one register (the fourth lane unused); min(p, low) is exactly std::min(low, p), and so on.
CLOTHCD_SIMD_AVX2 void bounds_avx2(const Vertices& points, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  low.setZero();
  high.setZero();
  if (points.rows() == 0) return;
  simd::d4::Doubles lo = simd::d4::load3(points.data()), hi = lo;
  for (Eigen::Index i = 1; i < points.rows(); ++i) {
    const simd::d4::Doubles p = simd::d4::load3(points.data() + 3 * i);
    lo = simd::d4::min(p, lo);
    hi = simd::d4::max(p, hi);
  }
  double l[4], h[4];
  simd::d4::store(l, lo);
  simd::d4::store(h, hi);
  low = Eigen::Vector3d(l[0], l[1], l[2]);
  high = Eigen::Vector3d(h[0], h[1], h[2]);
}

// Updates the running bests `best` and their rows `best_row` by `value` (row `row`): a strictly greater value
// replaces the running best and its row (so ties keep the first row); max(value, old) is value exactly where
// value > old.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void take_greater(double* best, double* best_row,
                                                                  simd::d4::Doubles value, simd::d4::Doubles row) {
  const simd::d4::Doubles old = simd::d4::load(best);
  simd::d4::store(best, simd::d4::max(value, old));
  simd::d4::store(best_row, simd::d4::select(value > old, row, simd::d4::load(best_row)));
}

// Updates `slab` (of axis a) by the point p (row `row`, distance `far` from the centre in lane 0, -infinity in the
// others).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void take_better(SlabBest& slab, const double* p, int a,
                                                                 simd::d4::Doubles far, simd::d4::Doubles row) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  take_greater(slab.extreme, slab.extreme_row, simd::d4::make(p[b], p[c], 0.0 - p[b], 0.0 - p[c]), row);
  take_greater(slab.far, slab.far_row, far, row);
}

// The running bests of every slab, updated point by point. The slab indices of a block of points are computed before
// the block's updates, so the updates' addresses are known early (else each load of a running best may wait for, or
// be replayed after, the stores of the point before, which often hit the same slab).
CLOTHCD_SIMD_AVX2 void slab_extremes_avx2(const Vertices& points, const Eigen::Vector3d& centre,
                                                        int slabs, int* rows) {
  Eigen::Vector3d low, high;
  bounds_avx2(points, low, high);
  const Slabs cut(low, high, slabs);
  const int slab_count = 3 * cut.count;
  std::array<SlabBest, 3 * kMaxSlabs> best;
  const double never = -std::numeric_limits<double>::infinity();
  std::fill_n(best.begin(), slab_count, SlabBest{{never, never, never, never}, {-1, -1, -1, -1},
                                                 {never, never, never, never}, {-1, -1, -1, -1}});
  // Slab of each axis as in Slabs::of, for x, y, z at once (the fourth lane unused), offset to the axis's slabs.
  const simd::d4::Doubles lo = simd::d4::make(cut.lo[0], cut.lo[1], cut.lo[2], 0.0);
  const simd::d4::Doubles inv_width = simd::d4::make(cut.inv_width[0], cut.inv_width[1], cut.inv_width[2], 0.0);
  const simd::I32x4 last = {cut.count - 1, cut.count - 1, cut.count - 1, cut.count - 1};
  const simd::I32x4 first_of_axis = {0, cut.count, 2 * cut.count, 0};
  constexpr int kBlock = 64;
  alignas(16) std::array<int, 4 * kBlock> slab_of;
  const Eigen::Index n = points.rows();
  for (Eigen::Index start = 0; start < n; start += kBlock) {
    const int count = static_cast<int>(std::min<Eigen::Index>(kBlock, n - start));
    for (int j = 0; j < count; ++j) {
      const simd::d4::Doubles p = simd::d4::load3(points.data() + 3 * (start + j));
      const simd::I32x4 slab = simd::d4::truncate((p - lo) * inv_width);
      const simd::I32x4 axis_slab = (slab < last ? slab : last) + first_of_axis;
      std::memcpy(slab_of.data() + 4 * j, &axis_slab, sizeof axis_slab);
    }
    for (int j = 0; j < count; ++j) {
      const double* p = points.data() + 3 * (start + j);
      const simd::d4::Doubles far = simd::d4::make(squared_distance(p, centre), never, never, never);
      const simd::d4::Doubles row = simd::d4::splat(double(start + j));
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

#endif

}  // namespace

void slab_extremes_reference(const Vertices& points, const Eigen::Vector3d& centre, int slabs, int* rows) {
  Eigen::Vector3d low, high;
  bounds(points, low, high);
  const Slabs cut(low, high, slabs);
  const int entries = 3 * cut.count * kSlabValues;
  std::array<double, 3 * kMaxSlabs * kSlabValues> score;
  std::fill_n(score.begin(), entries, -std::numeric_limits<double>::infinity());
  std::fill_n(rows, entries, -1);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double* p = points.data() + 3 * i;
    const double far = squared_distance(p, centre);
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const double values[kSlabValues] = {far, p[b], -p[b], p[c], -p[c]};
      const int base = (a * cut.count + cut.of(p, a)) * kSlabValues;
      for (int k = 0; k < kSlabValues; ++k) {
        if (values[k] > score[size_t(base + k)]) {
          score[size_t(base + k)] = values[k];
          rows[base + k] = int(i);
        }
      }
    }
  }
}

void slab_extremes(const Vertices& points, const Eigen::Vector3d& centre, int slabs, int* rows) {
#if defined(CLOTHCD_SIMD_X86)
  if (simd_level() >= SimdLevel::Avx2) return slab_extremes_avx2(points, centre, slabs, rows);
#endif
  slab_extremes_reference(points, centre, slabs, rows);
}

}  // namespace clothcd::geometry::detail
