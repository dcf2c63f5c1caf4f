// Pair features: translation and scale invariance, margins that agree with the plainly written filters, degenerate
// pairs, settings.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "clothcd/culling/pair_features.hpp"
#include "culling/pair_test_data.hpp"

using namespace clothcd::learning;
using clothcd::PairKind;
namespace ccd = clothcd::ccd;

namespace {

ccd::CcdQuery transformed(const ccd::CcdQuery& pair, double scale, const Eigen::Vector3d& offset) {
  ccd::CcdQuery out = pair;
  for (std::size_t k = 0; k < 4; ++k) {
    out.start[k] = scale * pair.start[k] + offset;
    out.end[k] = scale * pair.end[k] + offset;
  }
  return out;
}

std::vector<double> features_of(const ccd::CcdQuery& pair, std::size_t count = kMaxPairFeatures) {
  std::vector<double> out(count);
  compute_pair_features(pair, FeatureSettings{count}, out.data());
  return out;
}

}  // namespace

TEST_CASE("pair features are invariant to translation and uniform scale", "[learning][features]") {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const ccd::CcdQuery pair = test::random_pair(rng);
    const std::vector<double> base = features_of(pair);
    const std::vector<double> moved = features_of(transformed(pair, 1.0, Eigen::Vector3d(7.0, -3.0, 11.0)));
    const std::vector<double> scaled = features_of(transformed(pair, 250.0, Eigen::Vector3d::Zero()));
    for (std::size_t f = 0; f < kMaxPairFeatures; ++f) {
      CHECK(moved[f] == Approx(base[f]).margin(1e-9));
      CHECK(scaled[f] == Approx(base[f]).margin(1e-12));
      CHECK(std::abs(base[f]) <= 4.0);  // bounded: lengths / L, cube roots of volumes / L^3
    }
  }
}

TEST_CASE("the margin features are positive exactly when the reference filters remove the pair", "[learning][features]") {
  std::mt19937_64 rng(17);
  int removed = 0, kept = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const ccd::CcdQuery pair = test::random_pair(rng);
    const std::vector<double> f = features_of(pair);
    const double algebraic = f[1], projection = f[2];
    // Sign ties within rounding are not decided here; the data never lands on them in practice.
    if (std::abs(algebraic) > 1e-4) CHECK((algebraic > 0.0) == test::algebraic_filter_removes(pair));
    if (std::abs(projection) > 1e-6) CHECK((projection > 0.0) == test::projection_filter_removes(pair));
    double best = -1.0;
    for (int d = 3; d < 8; ++d) best = std::max(best, f[static_cast<std::size_t>(d)]);
    CHECK(projection == best);
    CHECK(f[0] == std::max(algebraic, projection));
    CHECK(f[14] == (pair.kind == PairKind::EdgeEdge ? 1.0 : 0.0));
    (test::filter_label(pair) == 0 ? removed : kept)++;
  }
  CHECK(removed > 200);  // both classes occur, so the agreement above means something
  CHECK(kept > 200);
}

TEST_CASE("a vertex moving straight through a face has no filter margin", "[learning][features]") {
  ccd::CcdQuery pair;
  pair.kind = PairKind::VertexFace;
  pair.start = {Eigen::Vector3d(0.2, 0.2, 1.0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  pair.end = pair.start;
  pair.end[0] = Eigen::Vector3d(0.2, 0.2, -1.0);  // crosses the triangle at t = 0.5: a real collision
  const std::vector<double> f = features_of(pair);
  CHECK(f[0] <= 0.0);
  CHECK(f[1] <= 0.0);
  CHECK(f[2] <= 0.0);
  CHECK(test::filter_label(pair) == 1);
  CHECK(test::exact_label(pair) == 1);
}

TEST_CASE("degenerate and invalid pairs give defined features", "[learning][features]") {
  ccd::CcdQuery point;
  for (std::size_t k = 0; k < 4; ++k) point.start[k] = point.end[k] = Eigen::Vector3d(1.0, 2.0, 3.0);
  for (const double value : features_of(point)) CHECK(value == 0.0);

  ccd::CcdQuery nan_pair = point;
  nan_pair.end[2].x() = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> f = features_of(nan_pair);
  CHECK_FALSE(std::isfinite(f[0]));
}

TEST_CASE("fewer features are the first ones of the full set", "[learning][features]") {
  std::mt19937_64 rng(29);
  for (int trial = 0; trial < 200; ++trial) {
    const ccd::CcdQuery pair = test::random_pair(rng);
    const std::vector<double> all = features_of(pair);
    for (std::size_t count = 1; count <= kMaxPairFeatures; ++count) {
      const std::vector<double> some = features_of(pair, count);
      for (std::size_t f = 0; f < count; ++f) CHECK(some[f] == all[f]);
    }
  }
}

TEST_CASE("feature count is a setting", "[learning][features]") {
  CHECK(pair_feature_names(FeatureSettings{}).size() == 15);
  CHECK(pair_feature_names(FeatureSettings{kMaxPairFeatures}).size() == kMaxPairFeatures);
  CHECK_THROWS_AS(pair_feature_names(FeatureSettings{0}), std::invalid_argument);
  CHECK_THROWS_AS(pair_feature_names(FeatureSettings{kMaxPairFeatures + 1}), std::invalid_argument);

  std::mt19937_64 rng(5);
  std::vector<ccd::CcdQuery> pairs;
  for (int i = 0; i < 10; ++i) pairs.push_back(test::random_pair(rng));
  PairFeatureBatch batch;
  compute_pair_features(pairs.data(), pairs.size(), FeatureSettings{12}, batch);
  REQUIRE(batch.features == 12);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::vector<double> row = features_of(pairs[i], 12);
    for (std::size_t f = 0; f < 12; ++f) CHECK(batch.column(f)[i] == row[f]);
  }
}
