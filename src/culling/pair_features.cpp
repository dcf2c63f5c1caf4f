// Features of a CCD candidate pair for the pair network (Jin et al., section 3.3.1: 15 inputs, not named there).
// They are built from what the paper's two filters look at, so that the network can learn their combined decision:
// - the coplanarity cubic D(t) = (x1 - x0)(t) x (x2 - x0)(t) . (x3 - x0)(t) (eqs. 6-7) in Bernstein form on [0, 1]: the
//   algebraic non-penetration filter removes a pair when all four coefficients have one strict sign (no root);
// - the spatial linear projection filter (eqs. 8-10): along each of the paper's five directions s, the projected gaps
//   between the two primitives at t = 0 and t = 1 all of one strict sign mean the projections never overlap.
// Each filter test becomes a signed margin (positive exactly when the filter removes the pair), scaled by the pair
// size L = diagonal of the box around the eight positions; datasets/README.md documents every feature.
#include "clothcd/culling/pair_features.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "ccd/pair_measures.hpp"
#include "culling/cube_root.hpp"
#include "culling/pair_feature_block.hpp"

namespace clothcd::learning {
namespace {

const char* const kFeatureNames[kMaxPairFeatures] = {
    "filter_margin", "algebraic_margin", "projection_margin", "projection_s1", "projection_s2", "projection_s3",
    "projection_s4", "projection_s5",    "bernstein_b0",      "bernstein_b1",  "bernstein_b2",  "bernstein_b3",
    "relative_motion", "gap_start",      "is_edge_edge",      "gap_end",       "area_start",    "area_end"};

// The differences of the projected gaps at both times (eqs. 8-9).
void gap_vectors(const ccd::CcdQuery& pair, Eigen::Vector3d (&gap)[2][4]) {
  const auto& points = ccd::pair_measures::kGapPoints[static_cast<int>(pair.kind)];
  for (int t = 0; t < 2; ++t) {
    const auto& x = t == 0 ? pair.start : pair.end;
    for (int j = 0; j < 4; ++j) {
      gap[t][j] = x[static_cast<std::size_t>(points[j][0])] - x[static_cast<std::size_t>(points[j][1])];
    }
  }
}

// Distance between the centres of the two primitives (vertex vs triangle centroid, edge midpoint vs edge midpoint).
double centre_gap(PairKind type, const std::array<Eigen::Vector3d, 4>& x) {
  if (type == PairKind::VertexFace) return (x[0] - (x[1] + x[2] + x[3]) / 3.0).norm();
  return (0.5 * (x[0] + x[1]) - 0.5 * (x[2] + x[3])).norm();
}

// Area of the triangle (vertex-face) or of the parallelogram spanned by the two edges (edge-edge: zero when parallel).
double primitive_area(PairKind type, const std::array<Eigen::Vector3d, 4>& x) {
  if (type == PairKind::VertexFace) return 0.5 * (x[2] - x[1]).cross(x[3] - x[1]).norm();
  return (x[1] - x[0]).cross(x[3] - x[2]).norm();
}

double pair_size(const ccd::CcdQuery& pair) {
  Eigen::Vector3d lo = pair.start[0], hi = pair.start[0];
  for (int k = 0; k < 4; ++k) {
    lo = lo.cwiseMin(pair.start[k]).cwiseMin(pair.end[k]);
    hi = hi.cwiseMax(pair.start[k]).cwiseMax(pair.end[k]);
  }
  return (hi - lo).norm();
}

}  // namespace

const char* pair_kind_name(PairKind kind) { return kind == PairKind::VertexFace ? "VF" : "EE"; }

std::vector<std::string> pair_feature_names(const FeatureSettings& settings) {
  if (settings.count < 1 || settings.count > kMaxPairFeatures)
    throw std::invalid_argument("feature count " + std::to_string(settings.count) + " is outside 1.." +
                                std::to_string(kMaxPairFeatures));
  return std::vector<std::string>(kFeatureNames, kFeatureNames + settings.count);
}

void compute_pair_features(const ccd::CcdQuery& pair, const FeatureSettings& settings, double* out) {
  double all[kMaxPairFeatures] = {};
  if (!detail::pair_coordinates_finite(pair)) {
    // Comparisons with NaN would turn into arbitrary margins: mark every feature invalid, the classifier keeps the pair.
    std::fill(out, out + std::min(settings.count, kMaxPairFeatures), std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const double size = pair_size(pair);
  // A pair of zero size cannot be scaled; all-zero features say "no margin", so the network cannot be sure to drop it.
  if (size > 0.0) {
    const double length_scale = 1.0 / size, volume_scale = length_scale * length_scale * length_scale;
    const std::array<double, 4> bernstein =
        ccd::pair_measures::coplanarity_bernstein(pair.start.data(), pair.end.data());
    // Cube roots of the volumes and signed square roots of the lengths keep the sign (the filters' decision at 0)
    // but spread the values near 0, where the decision is, over the min-max scaled range.
    all[1] = detail::cube_root(ccd::pair_measures::same_sign_margin(bernstein.data(), 4) * volume_scale);
    double best_projection = -1.0;
    Eigen::Vector3d gap[2][4];
    gap_vectors(pair, gap);
    for (int d = 0; d < 5; ++d) {
      const auto& unit = ccd::pair_measures::kProjectionDirections[static_cast<std::size_t>(d)].unit;
      const Eigen::Vector3d s(unit[0], unit[1], unit[2]);
      const double margin = ccd::pair_measures::projection_margin(gap, s) * length_scale;
      all[3 + d] = std::copysign(std::sqrt(std::abs(margin)), margin);
      best_projection = std::max(best_projection, all[3 + d]);
    }
    all[2] = best_projection;
    all[0] = std::max(all[1], all[2]);
    for (int k = 0; k < 4; ++k) all[8 + k] = detail::cube_root(bernstein[static_cast<std::size_t>(k)] * volume_scale);
    Eigen::Vector3d mean_motion = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) mean_motion += 0.25 * (pair.end[k] - pair.start[k]);
    double motion_squared = 0.0;
    for (int k = 0; k < 4; ++k) motion_squared += (pair.end[k] - pair.start[k] - mean_motion).squaredNorm();
    all[12] = std::sqrt(0.25 * motion_squared) * length_scale;
    all[13] = centre_gap(pair.kind, pair.start) * length_scale;
    // The extra features only when asked for (the default 15 stop before them).
    if (settings.count > 15) all[15] = centre_gap(pair.kind, pair.end) * length_scale;
    if (settings.count > 16) all[16] = primitive_area(pair.kind, pair.start) * length_scale * length_scale;
    if (settings.count > 17) all[17] = primitive_area(pair.kind, pair.end) * length_scale * length_scale;
  }
  all[14] = pair.kind == PairKind::EdgeEdge ? 1.0 : 0.0;
  std::copy(all, all + std::min(settings.count, kMaxPairFeatures), out);
}

void compute_pair_features(const ccd::CcdQuery* pairs, std::size_t count, const FeatureSettings& settings,
                           PairFeatureBatch& batch) {
  const std::size_t features = std::min(settings.count, kMaxPairFeatures);
  batch.resize(count, features);
  detail::compute_feature_blocks(pairs, count, features, simd_level(), batch);
}

}  // namespace clothcd::learning
