#pragma once
/// @file
/// Seeded random CCD pairs labelled by the CCD stage (combined filters -> filter label, safe exact CCD -> exact label):
/// a synthetic data set for tests and for a first model before simulation data sets exist. Identical on every platform
/// for a seed (SplitMix64, no std distributions).

#include <cstddef>

#include "clothcd/culling/pair_features.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::learning {

/// How the random pairs are drawn: four points uniform in [-1, 1]^3, each moving by up to `motion` per axis (before
/// scaling), the whole pair scaled by 10^U(-2, 2) and offset by up to 100 per axis; half vertex-face, half edge-edge.
struct RandomPairSettings {
  std::size_t rows = 5000;       ///< Pairs to draw.
  double motion = 1.5;           ///< Largest displacement per axis relative to the point spread.
  unsigned long long seed = 1;   ///< Seed of the pairs and of the 60/20/20 split.
  FeatureSettings features;      ///< Features to compute.
};

/// One random pair from the generator state `state` (advanced).
[[nodiscard]] ccd::CcdQuery random_pair(unsigned long long& state, double motion);

/// A labelled, split data set of random pairs (scene "random-pairs").
[[nodiscard]] PairDataset make_random_pair_dataset(const RandomPairSettings& settings);

}  // namespace clothcd::learning
