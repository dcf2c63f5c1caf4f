// Pair features in blocks (see pair_feature_block.hpp). Every expression below is the per-pair code's
// (pair_features.cpp) written lane by lane: the same operands, the same association, Eigen's order for its
// expressions (a 3-vector dot product or squared norm is (x0 y0 + x1 y1) + x2 y2), and the measures the filters share
// (ccd/pair_measures.hpp: eq. 10's directions, the Bernstein coefficients, the signed margins) from the same
// templates as the per-pair code.
#include "culling/pair_feature_block.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "ccd/pair_measures.hpp"
#include "culling/cube_root.hpp"
#include "support/simd.hpp"
#include "support/simd_level.hpp"

namespace clothcd::learning::detail {
namespace {

// Lanes per kernel step: half a ccd::PairLanes group.
constexpr int kLanes = 8;
constexpr int kGroupLanes = ccd::PairLanes::kLanes;
static_assert(kGroupLanes % kLanes == 0, "a lane group splits into whole kernel steps");

// One double per lane, and a 3-vector per lane, with the vector layer's element-wise operations.
using Lanes = simd::LaneArray<kLanes>;
using Vec3 = simd::LaneVector3<kLanes>;

[[gnu::always_inline]] inline Lanes lane_cbrt(const Lanes& a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r.v[l] = cube_root(a.v[l]);
  return r;
}

// kLanes pairs' positions on the vector layer, x[time][point], and is_edge_edge per lane (1 or 0).
struct GroupPositions {
  Vec3 x[2][4];
  Lanes is_edge_edge;
};

// kLanes lanes of a lane group from lane `first` on (the group's kind on every lane).
[[gnu::always_inline]] inline GroupPositions positions_of(const ccd::PairLanes& group, int first) {
  GroupPositions b;
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) std::memcpy(b.x[t][k].c[c].v, group.x[t][k][c] + first, sizeof b.x[t][k].c[c].v);
  const double edge_edge = group.kind == PairKind::EdgeEdge ? 1.0 : 0.0;
  for (int l = 0; l < kLanes; ++l) b.is_edge_edge.v[l] = edge_edge;
  return b;
}

// Lanes of `edge_edge` where the mask is 1, of `vertex_face` elsewhere.
[[gnu::always_inline]] inline Vec3 select(const Lanes& mask, const Vec3& edge_edge, const Vec3& vertex_face) {
  Vec3 r;
  for (int c = 0; c < 3; ++c)
    for (int l = 0; l < kLanes; ++l) r.c[c].v[l] = mask.v[l] != 0.0 ? edge_edge.c[c].v[l] : vertex_face.c[c].v[l];
  return r;
}

// The differences whose projections are the gaps of the projection filter at both times (pair_measures::kGapPoints
// of the lane's kind).
struct GapVectors {
  Vec3 d[2][4];
};

// Gap j at time t of every lane (the indices constants, so that no lane loop waits on an index).
template <std::size_t... J>
[[gnu::always_inline]] inline void gap_differences(const Vec3* x, const Lanes& is_edge_edge, Vec3 (&d)[4],
                                                   std::index_sequence<J...>) {
  constexpr auto& vf = ccd::pair_measures::kGapPoints[static_cast<int>(PairKind::VertexFace)];
  constexpr auto& ee = ccd::pair_measures::kGapPoints[static_cast<int>(PairKind::EdgeEdge)];
  ((d[J] = select(is_edge_edge, x[ee[J][0]] - x[ee[J][1]], x[vf[J][0]] - x[vf[J][1]])), ...);
}

[[gnu::always_inline]] inline GapVectors gap_vectors(const GroupPositions& b) {
  GapVectors g;
  for (int t = 0; t < 2; ++t) gap_differences(b.x[t], b.is_edge_edge, g.d[t], std::make_index_sequence<4>{});
  return g;
}

// Features of one block (all lanes filled) into out[f][lane] for f < kMaxPairFeatures.
[[gnu::always_inline]] inline void block_features(const GroupPositions& b, std::size_t features,
                                                  double (&out)[kMaxPairFeatures][kLanes]) {
  const Vec3* s = b.x[0];
  const Vec3* e = b.x[1];
  // Pair size: the diagonal of the box around the eight positions.
  Vec3 lo = s[0], hi = s[0];
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      lo.c[c] = lane_min(lane_min(lo.c[c], s[k].c[c]), e[k].c[c]);
      hi.c[c] = lane_max(lane_max(hi.c[c], s[k].c[c]), e[k].c[c]);
    }
  }
  const Lanes size = norm(hi - lo);
  Lanes length_scale, volume_scale;
  for (int l = 0; l < kLanes; ++l) {
    length_scale.v[l] = 1.0 / size.v[l];
    volume_scale.v[l] = length_scale.v[l] * length_scale.v[l] * length_scale.v[l];
  }
  // Bernstein coefficients of the coplanarity cubic.
  const std::array<Lanes, 4> bernstein = ccd::pair_measures::coplanarity_bernstein(s, e);
  const Lanes algebraic = lane_cbrt(ccd::pair_measures::same_sign_margin(bernstein.data(), 4) * volume_scale);
  Lanes bernstein_roots[4];
  for (int k = 0; k < 4; ++k) bernstein_roots[k] = lane_cbrt(bernstein[static_cast<std::size_t>(k)] * volume_scale);
  Lanes best;
  for (int l = 0; l < kLanes; ++l) best.v[l] = -1.0;
  Lanes projections[5];
  const GapVectors gaps = gap_vectors(b);
  for (int d = 0; d < 5; ++d) {
    const auto& direction = ccd::pair_measures::kProjectionDirections[static_cast<std::size_t>(d)];
    const Lanes margin = ccd::pair_measures::projection_margin(gaps.d, direction.unit.data()) * length_scale;
    for (int l = 0; l < kLanes; ++l)
      projections[d].v[l] = std::copysign(std::sqrt(std::abs(margin.v[l])), margin.v[l]);
    best = lane_max(best, projections[d]);
  }
  // Relative motion: spread of the four displacements around their mean.
  Vec3 mean_motion;
  for (int c = 0; c < 3; ++c)
    for (int l = 0; l < kLanes; ++l) mean_motion.c[c].v[l] = 0.0;
  for (int k = 0; k < 4; ++k) mean_motion = mean_motion + 0.25 * (e[k] - s[k]);
  Lanes motion_squared;
  for (int l = 0; l < kLanes; ++l) motion_squared.v[l] = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 d = (e[k] - s[k]) - mean_motion;
    motion_squared = motion_squared + dot(d, d);
  }
  const Lanes motion = lane_sqrt(0.25 * motion_squared) * length_scale;
  // Centre gap at the start: vertex to triangle centroid, or edge midpoint to edge midpoint.
  const Vec3 vf_gap = s[0] - (s[1] + s[2] + s[3]) / 3.0;
  const Vec3 ee_gap = 0.5 * (s[0] + s[1]) - 0.5 * (s[2] + s[3]);
  const Lanes vf_centre = norm(vf_gap) * length_scale, ee_centre = norm(ee_gap) * length_scale;

  for (int l = 0; l < kLanes; ++l) {
    double all[kMaxPairFeatures] = {};
    if (size.v[l] > 0.0) {
      all[1] = algebraic.v[l];
      for (int d = 0; d < 5; ++d) all[3 + d] = projections[d].v[l];
      all[2] = best.v[l];
      all[0] = std::max(all[1], all[2]);
      for (int k = 0; k < 4; ++k) all[8 + k] = bernstein_roots[k].v[l];
      all[12] = motion.v[l];
      all[13] = b.is_edge_edge.v[l] != 0.0 ? ee_centre.v[l] : vf_centre.v[l];
    }
    all[14] = b.is_edge_edge.v[l];
    for (std::size_t f = 0; f < features && f < 15; ++f) out[f][l] = all[f];
  }
}

// Writes the features `out` of lanes [0, used) to rows row_of(l) of `batch` (its values for `count` rows); pair_of(l)
// is lane l's pair (for the finiteness check and the extra features).
template <class RowOf, class PairOf>
[[gnu::always_inline]] inline void write_rows(const double (&out)[kMaxPairFeatures][kLanes], int used,
                                              const RowOf& row_of, const PairOf& pair_of, std::size_t features,
                                              std::size_t count, PairFeatureBatch& batch) {
  const std::size_t dense = std::min<std::size_t>(features, 15);
  for (int l = 0; l < used; ++l) {
    const std::size_t i = row_of(l);
    const ccd::CcdQuery& pair = pair_of(l);
    if (!pair_coordinates_finite(pair)) {
      for (std::size_t f = 0; f < features; ++f) batch.values[f * count + i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    for (std::size_t f = 0; f < dense; ++f) batch.values[f * count + i] = out[f][l];
    if (features > 15) {  // the extra features, per pair
      double extra[kMaxPairFeatures];
      compute_pair_features(pair, FeatureSettings{features}, extra);
      for (std::size_t f = 15; f < features; ++f) batch.values[f * count + i] = extra[f];
    }
  }
}

// ccd::PairLanes::query, inlined here (the lane group's own is in the core library).
[[gnu::always_inline]] inline ccd::CcdQuery lane_query(const ccd::PairLanes& group, int lane) {
  ccd::CcdQuery q;
  q.kind = group.kind;
  for (int k = 0; k < 4; ++k) {
    q.start[k] = Eigen::Vector3d(group.x[0][k][0][lane], group.x[0][k][1][lane], group.x[0][k][2][lane]);
    q.end[k] = Eigen::Vector3d(group.x[1][k][0][lane], group.x[1][k][1][lane], group.x[1][k][2][lane]);
  }
  return q;
}

// The pairs of `block`, straight from its lane groups, kLanes lanes at a time.
[[gnu::always_inline]] inline void blocks(const ccd::PairBlock& block, std::size_t features, PairFeatureBatch& batch) {
  const auto count = static_cast<std::size_t>(block.size());
  double out[kMaxPairFeatures][kLanes];
  for (std::size_t first = 0; first < count; first += kLanes) {
    const int used = static_cast<int>(std::min<std::size_t>(kLanes, count - first));
    const ccd::PairLanes& group = block.group(static_cast<int>(first / kGroupLanes));
    const int lane = static_cast<int>(first % kGroupLanes);
    block_features(positions_of(group, lane), features, out);
    write_rows(
        out, used, [&](int l) { return first + static_cast<std::size_t>(l); },
        [&](int l) { return lane_query(group, lane + l); }, features, count, batch);
  }
}

// The pairs of `pairs` (of either kind), gathered kLanes at a time.
[[gnu::always_inline]] inline void blocks(const ccd::CcdQuery* pairs, std::size_t count, std::size_t features,
                                          PairFeatureBatch& batch) {
  double out[kMaxPairFeatures][kLanes];
  for (std::size_t first = 0; first < count; first += kLanes) {
    const int used = static_cast<int>(std::min<std::size_t>(kLanes, count - first));
    GroupPositions b;
    for (int l = 0; l < kLanes; ++l) {
      const ccd::CcdQuery& p = pairs[first + static_cast<std::size_t>(l < used ? l : 0)];
      for (int k = 0; k < 4; ++k) {
        for (int c = 0; c < 3; ++c) {
          b.x[0][k].c[c].v[l] = p.start[k][c];
          b.x[1][k].c[c].v[l] = p.end[k][c];
        }
      }
      b.is_edge_edge.v[l] = p.kind == PairKind::EdgeEdge ? 1.0 : 0.0;
    }
    block_features(b, features, out);
    write_rows(
        out, used, [&](int l) { return first + static_cast<std::size_t>(l); },
        [&](int l) -> const ccd::CcdQuery& { return pairs[first + static_cast<std::size_t>(l)]; }, features, count,
        batch);
  }
}

// Both forms of the blocks compiled for every level (the same features at each).
#define CLOTHCD_SIMD_KERNEL_FUNCTION blocks
#define CLOTHCD_SIMD_KERNEL_AVX512
#include "support/simd_versions.hpp"

}  // namespace

bool pair_coordinates_finite(const ccd::CcdQuery& pair) {
  double coordinate_sum = 0.0;
  for (std::size_t k = 0; k < 4; ++k) coordinate_sum += pair.start[k].sum() + pair.end[k].sum();
  return std::isfinite(coordinate_sum);
}

void compute_feature_blocks(const ccd::CcdQuery* pairs, std::size_t count, std::size_t features, SimdLevel level,
                            PairFeatureBatch& batch) {
  CLOTHCD_SIMD_DISPATCH(level, run_kernel(pairs, count, features, batch));
}

void compute_feature_blocks(const ccd::PairBlock& block, std::size_t features, SimdLevel level,
                            PairFeatureBatch& batch) {
  CLOTHCD_SIMD_DISPATCH(level, run_kernel(block, features, batch));
}

}  // namespace clothcd::learning::detail
