// Outward rounding from double to float: a bound of magnitude below 1e38 moved outwards by 2^-22 of its magnitude
// (plus 1e-30, a normal float, for bounds near zero) before the round-to-nearest conversion cannot come back past the
// original value, since that conversion moves it by at most 2^-24 of its magnitude (or half a subnormal step), and it
// stays below the largest float. Bounds of magnitude 1e38 or more (and infinities) get a fixed float on the
// conservative side: 9e37 below a huge positive value, -infinity below a huge negative one, and symmetrically above.
#include "broadphase/packed_boxes.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "support/simd.hpp"
#include "support/simd_level.hpp"

namespace clothcd::broadphase {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr double kLargeBound = 1e38;
constexpr float kBelowLargeBound = 9e37f;

// The common case is one predictable branch and five arithmetic instructions.
inline float round_down(double x) {
  const double magnitude = std::fabs(x);
  if (magnitude < kLargeBound) return static_cast<float>(x - (magnitude * 0x1p-22 + 1e-30));
  return x > 0.0 ? kBelowLargeBound : -kInfinity;  // NaN also lands here: with round_up's, an unbounded box
}

inline float round_up(double x) {
  const double magnitude = std::fabs(x);
  if (magnitude < kLargeBound) return static_cast<float>(x + (magnitude * 0x1p-22 + 1e-30));
  return x < 0.0 ? -kBelowLargeBound : kInfinity;
}

// Four bounds x[0..3] rounded outwards (kUpper: up, else down) into out[0..3]: round_up/round_down with selects
// instead of branches, bit for bit the same floats.
template <bool kUpper>
[[gnu::always_inline]] inline void round_four(const double* x, float* out) {
  using Doubles4 = simd::F64x4;
  using Floats4 = simd::F32x4;
  constexpr double kInfinityDouble = std::numeric_limits<double>::infinity();
  constexpr double kBelowLarge = kBelowLargeBound;  // exact in double; converts back to kBelowLargeBound
  Doubles4 v;
  std::memcpy(&v, x, sizeof v);
  const Doubles4 magnitude = v < 0.0 ? -v : v;
  const Doubles4 step = magnitude * 0x1p-22 + 1e-30;
  const Doubles4 moved = kUpper ? v + step : v - step;
  const Doubles4 large = kUpper ? (v < 0.0 ? Doubles4{} - kBelowLarge : Doubles4{} + kInfinityDouble)
                                : (v > 0.0 ? Doubles4{} + kBelowLarge : Doubles4{} - kInfinityDouble);
  // Only the lanes below 1e38 convert a moved value (and NaN takes `large`, like the scalar versions).
  const Floats4 rounded = __builtin_convertvector(magnitude < kLargeBound ? moved : large, Floats4);
  std::memcpy(out, &rounded, sizeof rounded);
}

// The six rows of boxes [0, n) four boxes at a time (rows of `stride` floats from `r`); returns how many boxes it wrote
// (a multiple of four).
[[gnu::always_inline]] inline int round_rows(const FlatBox* boxes, int n, float* r, int stride) {
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    const FlatBox* b = boxes + j;
    for (int k = 0; k < 3; ++k) {
      const double lower[4] = {b[0].min[k], b[1].min[k], b[2].min[k], b[3].min[k]};
      const double upper[4] = {b[0].max[k], b[1].max[k], b[2].max[k], b[3].max[k]};
      round_four<false>(lower, r + k * stride + j);
      round_four<true>(upper, r + (3 + k) * stride + j);
    }
  }
  return j;
}

// round_rows compiled for AVX2 (the baseline rounds box by box below).
#define CLOTHCD_SIMD_KERNEL_FUNCTION round_rows
#define CLOTHCD_SIMD_KERNEL_WIDE
#include "support/simd_versions.hpp"

}  // namespace

PackedBox pack_box(const FlatBox& box) {
  PackedBox p;
  for (int k = 0; k < 3; ++k) {
    p.lo[k] = round_down(box.min[k]);
    p.hi[k] = round_up(box.max[k]);
  }
  return p;
}

void PackedBoxes::assign(const std::vector<FlatBox>& boxes) {
  size_ = static_cast<int>(boxes.size());
  stride_ = size_ + kPackedPadding;
  rows_.resize(6 * static_cast<std::size_t>(stride_));
  float* r = rows_.data();
  int j = CLOTHCD_SIMD_DISPATCH_WIDE(simd_level(), run_kernel(boxes.data(), size_, r, stride_), 0);
  for (; j < size_; ++j) {
    const FlatBox& b = boxes[j];
    for (int k = 0; k < 3; ++k) {
      r[k * stride_ + j] = round_down(b.min[k]);
      r[(3 + k) * stride_ + j] = round_up(b.max[k]);
    }
  }
  for (int j = size_; j < stride_; ++j) {  // padding: an empty box overlaps nothing
    for (int k = 0; k < 3; ++k) {
      r[k * stride_ + j] = kInfinity;
      r[(3 + k) * stride_ + j] = -kInfinity;
    }
  }
}

void PackedVertexIds::assign(const std::vector<int>& ids, int per_primitive) {
  const int count = static_cast<int>(ids.size()) / per_primitive;
  stride_ = count + kPackedPadding;
  rows_.assign(static_cast<std::size_t>(per_primitive) * static_cast<std::size_t>(stride_), -1);
  for (int j = 0; j < count; ++j) {
    for (int row = 0; row < per_primitive; ++row) rows_[row * stride_ + j] = ids[per_primitive * j + row];
  }
}

}  // namespace clothcd::broadphase
