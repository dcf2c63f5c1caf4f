#pragma once
// Seeded random CCD pairs for the learning tests (until the dataset generator feeds simulation pairs), labelled by the
// CCD stage's filters and exact CCD, plus a plainly written reference of the paper's two filters that the feature
// margins are checked against. Small and fast.

#include <array>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "clothcd/culling/pair_features.hpp"
#include "clothcd/learning/pair_dataset.hpp"
#include "clothcd/learning/random_pairs.hpp"

namespace clothcd::learning::test {

/// Random pair in a random frame (the library's generator, seeded from `rng`).
inline ccd::CcdQuery random_pair(std::mt19937_64& rng) {
  unsigned long long state = rng();
  return clothcd::learning::random_pair(state, 1.5);
}

/// D(t) = (x1 - x0) x (x2 - x0) . (x3 - x0) at time t.
inline double coplanarity(const ccd::CcdQuery& pair, double t) {
  auto x = [&](int k) {
    return Eigen::Vector3d((1.0 - t) * pair.start[static_cast<std::size_t>(k)] + t * pair.end[static_cast<std::size_t>(k)]);
  };
  return (x(1) - x(0)).cross(x(2) - x(0)).dot(x(3) - x(0));
}

/// D'(t) by the product rule.
inline double coplanarity_derivative(const ccd::CcdQuery& pair, double t) {
  auto x = [&](int k) {
    return Eigen::Vector3d((1.0 - t) * pair.start[static_cast<std::size_t>(k)] + t * pair.end[static_cast<std::size_t>(k)]);
  };
  auto v = [&](int k) { return Eigen::Vector3d(pair.end[static_cast<std::size_t>(k)] - pair.start[static_cast<std::size_t>(k)]); };
  const Eigen::Vector3d p1 = x(1) - x(0), p2 = x(2) - x(0), p3 = x(3) - x(0);
  const Eigen::Vector3d v1 = v(1) - v(0), v2 = v(2) - v(0), v3 = v(3) - v(0);
  return v1.cross(p2).dot(p3) + p1.cross(v2).dot(p3) + p1.cross(p2).dot(v3);
}

/// True when the algebraic filter removes the pair: the Bernstein coefficients D(0), D(0) + D'(0)/3, D(1) - D'(1)/3,
/// D(1) all have one strict sign.
inline bool algebraic_filter_removes(const ccd::CcdQuery& pair) {
  const double b[4] = {coplanarity(pair, 0.0), coplanarity(pair, 0.0) + coplanarity_derivative(pair, 0.0) / 3.0,
                       coplanarity(pair, 1.0) - coplanarity_derivative(pair, 1.0) / 3.0, coplanarity(pair, 1.0)};
  bool positive = true, negative = true;
  for (const double c : b) positive &= c > 0.0, negative &= c < 0.0;
  return positive || negative;
}

/// True when the projection filter (eqs. 8-10) removes the pair along one of the paper's five directions.
inline bool projection_filter_removes(const ccd::CcdQuery& pair) {
  const double r2 = std::sqrt(2.0) / 2.0, r3 = std::sqrt(3.0) / 3.0;
  const Eigen::Vector3d directions[5] = {{1, 0, 0}, {r2, r2, 0}, {r2, 0, r2}, {0, r2, r2}, {r3, r3, r3}};
  for (const Eigen::Vector3d& s : directions) {
    bool positive = true, negative = true;
    for (const auto* x : {&pair.start, &pair.end}) {
      const auto& p = *x;
      if (pair.kind == PairKind::VertexFace) {
        for (int k = 1; k < 4; ++k) {
          const double z = (p[0] - p[static_cast<std::size_t>(k)]).dot(s);
          positive &= z > 0.0, negative &= z < 0.0;
        }
      } else {
        for (int a = 0; a < 2; ++a)
          for (int b = 2; b < 4; ++b) {
            const double z = (p[static_cast<std::size_t>(a)] - p[static_cast<std::size_t>(b)]).dot(s);
            positive &= z > 0.0, negative &= z < 0.0;
          }
      }
    }
    if (positive || negative) return true;
  }
  return false;
}

/// The paper's label, from the CCD stage's own filters: 0 when the combined filters remove the pair.
inline int filter_label(const ccd::CcdQuery& pair) { return ccd::combined_filters_cull(pair) ? 0 : 1; }

/// The exact label from the CCD stage's safe narrow phase: 1 when the pair collides during the step.
inline int exact_label(const ccd::CcdQuery& pair) {
  ccd::CcdSettings exact;
  exact.decide_exactly = true;
  return ccd::continuous_collision(pair, exact).hit ? 1 : 0;
}

/// `rows` labelled random pairs with `feature_count` features, split 60/20/20 from `seed`.
inline PairDataset make_pair_dataset(std::size_t rows, unsigned long long seed, std::size_t feature_count = 15) {
  RandomPairSettings settings;
  settings.rows = rows;
  settings.seed = seed;
  settings.features.count = feature_count;
  return make_random_pair_dataset(settings);
}

}  // namespace clothcd::learning::test
