// Synthetic labelled pairs: random linear motions of four points, labelled with the paper's combined filters
// (sections 2.2-2.3, clothcd::ccd::combined_filters_cull) and the safe exact CCD (ccd::continuous_collision).
#include "clothcd/learning/random_pairs.hpp"

#include <cmath>
#include <vector>

#include "learning/split_mix64.hpp"

namespace clothcd::learning {
namespace {

// Uniform in [-1, 1).
double symmetric_unit(unsigned long long& state) {
  return 2.0 * static_cast<double>(split_mix64_next(state) >> 11) * 0x1.0p-53 - 1.0;
}

}  // namespace

ccd::CcdQuery random_pair(unsigned long long& state, double motion) {
  ccd::CcdQuery pair;
  pair.kind = split_mix64_next(state) % 2 ? PairKind::EdgeEdge : PairKind::VertexFace;
  const double scale = std::pow(10.0, 2.0 * symmetric_unit(state));
  Eigen::Vector3d offset;
  for (int a = 0; a < 3; ++a) offset[a] = 100.0 * symmetric_unit(state);
  for (std::size_t k = 0; k < 4; ++k) {
    Eigen::Vector3d p, d;
    for (int a = 0; a < 3; ++a) p[a] = symmetric_unit(state);
    for (int a = 0; a < 3; ++a) d[a] = symmetric_unit(state);
    pair.start[k] = offset + scale * p;
    pair.end[k] = offset + scale * (p + motion * d);
  }
  return pair;
}

PairDataset make_random_pair_dataset(const RandomPairSettings& settings) {
  PairDataset dataset;
  dataset.feature_names = pair_feature_names(settings.features);
  std::vector<double> features(dataset.feature_count());
  unsigned long long state = settings.seed;
  ccd::CcdSettings exact;  // thickness 0
  exact.decide_exactly = true;
  for (std::size_t i = 0; i < settings.rows; ++i) {
    const ccd::CcdQuery pair = random_pair(state, settings.motion);
    compute_pair_features(pair, settings.features, features.data());
    PairRow row;
    row.features = features.data();
    row.filter_label = ccd::combined_filters_cull(pair) ? 0 : 1;
    row.exact_label = ccd::continuous_collision(pair, exact).hit ? 1 : 0;
    row.type = pair.kind;
    row.scene = "random-pairs";
    dataset.add_row(row);
  }
  assign_splits(dataset, SplitSettings{0.6, 0.2, settings.seed});
  return dataset;
}

}  // namespace clothcd::learning
