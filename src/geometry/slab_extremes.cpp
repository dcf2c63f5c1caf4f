// Slab extremes of the fast adaptive OBB (Jin et al. eqs. 15-16). Which row wins a slab is data-dependent, so the
// reference's branches are often mispredicted; the fast version (x86-64 with AVX2, chosen at run time) updates each
// slab's running bests with comparison masks instead, four values at a time.
#include "slab_extremes.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

#include "support/simd.hpp"
#include "support/simd_level.hpp"


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

// The wide kernel: the running bests on four double lanes.
#define CLOTHCD_SIMD_KERNEL "geometry/slab_extremes_lanes.hpp"
#define CLOTHCD_SIMD_KERNEL_WIDE
#include "support/simd_versions.hpp"

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
  CLOTHCD_SIMD_DISPATCH_WIDE(simd_level(), slab_extremes(points, centre, slabs, rows),
                             slab_extremes_reference(points, centre, slabs, rows));
}

}  // namespace clothcd::geometry::detail
