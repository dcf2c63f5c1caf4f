// The batch features (blocks of pairs, vectorized) against the per-pair features: bit for bit, on seeded random pairs
// and degenerate ones, on every instruction set this CPU runs.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "clothcd/ccd/pair_block.hpp"
#include "clothcd/culling/pair_features.hpp"
#include "culling/pair_feature_block.hpp"
#include "culling/pair_test_data.hpp"
#include "support/simd_level.hpp"

using namespace clothcd::learning;
using clothcd::PairKind;
namespace ccd = clothcd::ccd;
using clothcd::cpu_simd_levels;
using clothcd::simd_level_name;
using clothcd::SimdLevel;

namespace {

// Degenerate pairs: a point, a tiny pair, a huge one, coplanar and parallel primitives, non-finite coordinates.
std::vector<ccd::CcdQuery> degenerate_pairs() {
  std::vector<ccd::CcdQuery> pairs;
  std::mt19937_64 rng(5);
  for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
    ccd::CcdQuery point;
    point.kind = kind;
    for (std::size_t k = 0; k < 4; ++k) point.start[k] = point.end[k] = Eigen::Vector3d(1.0, -2.0, 3.0);
    pairs.push_back(point);
    for (const double scale : {1e-300, 1e-150, 1e150, 1e300}) {
      ccd::CcdQuery p = test::random_pair(rng);
      p.kind = kind;
      for (std::size_t k = 0; k < 4; ++k) {
        p.start[k] *= scale;
        p.end[k] *= scale;
      }
      pairs.push_back(p);
    }
    ccd::CcdQuery flat = test::random_pair(rng);  // everything in the plane z = 0 for the whole step
    flat.kind = kind;
    for (std::size_t k = 0; k < 4; ++k) flat.start[k].z() = flat.end[k].z() = 0.0;
    pairs.push_back(flat);
    ccd::CcdQuery still = test::random_pair(rng);  // no motion
    still.kind = kind;
    still.end = still.start;
    pairs.push_back(still);
    ccd::CcdQuery parallel = still;  // edge 2-3 a copy of edge 0-1 moved along x
    for (std::size_t k = 2; k < 4; ++k) parallel.start[k] = parallel.end[k] = still.start[k - 2] + Eigen::Vector3d(0.5, 0, 0);
    pairs.push_back(parallel);
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()}) {
      ccd::CcdQuery p = test::random_pair(rng);
      p.kind = kind;
      p.end[3].y() = bad;
      pairs.push_back(p);
    }
    ccd::CcdQuery overflow = test::random_pair(rng);  // finite coordinates whose sum overflows
    overflow.kind = kind;
    for (std::size_t k = 0; k < 4; ++k) overflow.start[k].x() = overflow.end[k].x() = 1.5e308;
    pairs.push_back(overflow);
  }
  return pairs;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

void check_against_per_pair(const std::vector<ccd::CcdQuery>& pairs, std::size_t features) {
  for (const SimdLevel level : cpu_simd_levels()) {
    PairFeatureBatch batch;
    batch.resize(pairs.size(), features);
    detail::compute_feature_blocks(pairs.data(), pairs.size(), features, level, batch);
    std::vector<double> row(features);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      compute_pair_features(pairs[i], FeatureSettings{features}, row.data());
      for (std::size_t f = 0; f < features; ++f) {
        INFO("pair " << i << " feature " << f << " level " << simd_level_name(level) << ": " << batch.column(f)[i] << " vs " << row[f]);
        CHECK(same_bits(batch.column(f)[i], row[f]));
      }
    }
  }
}

// The features of each kind's pairs read straight from a ccd::PairBlock (as the network culler reads them) against
// the per-pair features, at every level.
void check_block_against_per_pair(const std::vector<ccd::CcdQuery>& pairs, std::size_t features) {
  for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
    std::vector<const ccd::CcdQuery*> of_kind;
    for (const ccd::CcdQuery& pair : pairs) {
      if (pair.kind == kind) of_kind.push_back(&pair);
    }
    if (of_kind.empty()) continue;
    ccd::PairBlock block(static_cast<int>(of_kind.size()));
    block.reset(kind);
    for (const ccd::CcdQuery* pair : of_kind) {
      std::array<const double*, 4> start{}, end{};
      for (std::size_t k = 0; k < 4; ++k) {
        start[k] = pair->start[k].data();
        end[k] = pair->end[k].data();
      }
      block.push({}, 0, start, end);
    }
    for (const SimdLevel level : cpu_simd_levels()) {
      PairFeatureBatch batch;
      batch.resize(of_kind.size(), features);
      detail::compute_feature_blocks(block, features, level, batch);
      std::vector<double> row(features);
      for (std::size_t i = 0; i < of_kind.size(); ++i) {
        compute_pair_features(*of_kind[i], FeatureSettings{features}, row.data());
        for (std::size_t f = 0; f < features; ++f) {
          INFO("block pair " << i << " feature " << f << " level " << simd_level_name(level));
          CHECK(same_bits(batch.column(f)[i], row[f]));
        }
      }
    }
  }
}

}  // namespace

TEST_CASE("batch features from a pair block equal the per-pair features bit for bit", "[learning][features]") {
  std::mt19937_64 rng(47);
  std::vector<ccd::CcdQuery> pairs;
  for (int i = 0; i < 1001; ++i) pairs.push_back(test::random_pair(rng));  // groups of both kinds, the last short
  check_block_against_per_pair(pairs, 15);
  check_block_against_per_pair(pairs, kMaxPairFeatures);
  check_block_against_per_pair(degenerate_pairs(), 15);
}

TEST_CASE("batch features equal the per-pair features bit for bit", "[learning][features]") {
  std::mt19937_64 rng(41);
  std::vector<ccd::CcdQuery> pairs;
  for (int i = 0; i < 3001; ++i) pairs.push_back(test::random_pair(rng));  // not a multiple of the block size
  for (const std::size_t features : {std::size_t{15}, std::size_t{1}, std::size_t{9}, kMaxPairFeatures}) {
    check_against_per_pair(pairs, features);
  }
  check_against_per_pair(degenerate_pairs(), 15);
  check_against_per_pair(degenerate_pairs(), kMaxPairFeatures);
}

TEST_CASE("batch features equal the per-pair features bit for bit on grid pairs (signed zeros)", "[learning][features]") {
  // Small integer coordinates: many equal gaps, among them zeros of both signs, where a margin's extreme could pick
  // either of two equal zeros.
  std::mt19937_64 rng(53);
  std::uniform_int_distribution<int> coordinate(-2, 2);
  std::vector<ccd::CcdQuery> pairs(4000);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    pairs[i].kind = i % 2 == 0 ? PairKind::VertexFace : PairKind::EdgeEdge;
    for (std::size_t k = 0; k < 4; ++k) {
      pairs[i].start[k] = Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
      pairs[i].end[k] = Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    }
  }
  check_against_per_pair(pairs, 15);
  check_block_against_per_pair(pairs, 15);
}

TEST_CASE("batch features of no pairs and of one pair", "[learning][features]") {
  PairFeatureBatch batch;
  compute_pair_features(nullptr, 0, FeatureSettings{}, batch);
  CHECK(batch.rows == 0);
  std::mt19937_64 rng(43);
  check_against_per_pair({test::random_pair(rng)}, 15);
}
