// Outward rounding from double to float: a bound moved outwards by 2^-22 of its magnitude (plus 1e-30, a normal float,
// for bounds near zero) before the round-to-nearest conversion cannot come back past the original value, since that
// conversion moves it by at most 2^-24 of its magnitude (or half a subnormal step). Bounds beyond the float range are
// clamped to the largest float on the side that keeps them conservative (infinity on the outer side is fine).
#include "clothcd/broadphase/packed_boxes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clothcd::broadphase {
namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr double kBeyondFloat = 1e39;

// Bounds are first clamped to +-1e39 (beyond the float range, so the clamp never crosses a float bound and maps
// infinities to finite values). The conditional expressions compile to min/max instructions, not branches.
float round_down(double x) {
  double v = x < -kBeyondFloat ? -kBeyondFloat : x;
  v = v > kBeyondFloat ? kBeyondFloat : v;
  v -= std::fabs(v) * 0x1p-22 + 1e-30;
  return static_cast<float>(v > kFloatMax ? kFloatMax : v);
}

float round_up(double x) {
  double v = x < -kBeyondFloat ? -kBeyondFloat : x;
  v = v > kBeyondFloat ? kBeyondFloat : v;
  v += std::fabs(v) * 0x1p-22 + 1e-30;
  return static_cast<float>(v < -kFloatMax ? -kFloatMax : v);
}

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
  stride_ = size_ + 3;
  rows_.resize(6 * static_cast<std::size_t>(stride_));
  float* r = rows_.data();
  for (int j = 0; j < size_; ++j) {
    const PackedBox p = pack_box(boxes[j]);
    for (int k = 0; k < 3; ++k) {
      r[k * stride_ + j] = p.lo[k];
      r[(3 + k) * stride_ + j] = p.hi[k];
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
  stride_ = count + 3;
  rows_.assign(static_cast<std::size_t>(per_primitive) * static_cast<std::size_t>(stride_), -1);
  for (int j = 0; j < count; ++j) {
    for (int row = 0; row < per_primitive; ++row) rows_[row * stride_ + j] = ids[per_primitive * j + row];
  }
}

}  // namespace clothcd::broadphase
