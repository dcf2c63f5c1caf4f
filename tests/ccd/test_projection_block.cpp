// The block projection filter (ccd/projection_block.hpp, the detector's fast path) against the per-pair filter it
// replaces (projection_filter_culls, the reference): the same verdict on seeded random, resting and degenerate pairs in
// blocks of every fill, and never a culled pair that comes within the thickness.
#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "ccd/projection_block.hpp"
#include "ccd/sampled_distance.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "support/simd_level.hpp"

namespace {

using clothcd::PairKind;
using Eigen::Vector3d;
namespace ccd = clothcd::ccd;

class PairMaker {
 public:
  explicit PairMaker(unsigned seed) : random_(seed) {}

  // Points anywhere in a box of `extent`, moving up to `motion`.
  ccd::CcdQuery random_pair(PairKind kind, double extent, double motion) {
    ccd::CcdQuery q;
    q.kind = kind;
    for (int i = 0; i < 4; ++i) {
      q.start[i] = vector(extent);
      q.end[i] = q.start[i] + vector(motion);
    }
    return q;
  }

  // A small pair whose primitives start about `gap` apart along a random normal (a cloth resting at the thickness).
  ccd::CcdQuery resting_pair(PairKind kind, double gap) {
    const Vector3d normal = vector(1.0).normalized();
    const Vector3d tangent = normal.unitOrthogonal();
    const Vector3d bitangent = normal.cross(tangent);
    const Vector3d origin = vector(1.0);
    const double size = 0.02;
    ccd::CcdQuery q;
    q.kind = kind;
    if (kind == PairKind::VertexFace) {
      q.start[1] = origin + size * (-0.5 * tangent - 0.5 * bitangent);
      q.start[2] = origin + size * (tangent - 0.3 * bitangent);
      q.start[3] = origin + size * (-0.2 * tangent + bitangent);
      q.start[0] = origin + size * uniform(-0.3, 0.3) * tangent + gap * normal;
    } else {
      q.start[0] = origin + gap * normal - size * tangent;
      q.start[1] = origin + gap * normal + size * tangent;
      q.start[2] = origin - size * bitangent;
      q.start[3] = origin + size * bitangent;
    }
    for (int i = 0; i < 4; ++i) q.end[i] = q.start[i] + vector(0.1 * gap);
    return q;
  }

  // Dyadic grid coordinates: coincident points, zero-area faces, zero-length and parallel edges, no motion.
  ccd::CcdQuery degenerate_pair(PairKind kind) {
    ccd::CcdQuery q;
    q.kind = kind;
    std::uniform_int_distribution<int> step(-2, 2);
    auto grid = [&]() {
      Vector3d v;
      for (int c = 0; c < 3; ++c) v[c] = 0.25 * step(random_);
      return v;
    };
    for (int i = 0; i < 4; ++i) {
      q.start[i] = grid();
      q.end[i] = coin() ? q.start[i] : grid();
    }
    if (coin()) q.start[pick()] = q.start[pick()];
    if (coin()) q.end[pick()] = q.end[pick()];
    if (coin()) {  // collinear corners / parallel edges
      q.start[3] = q.start[2] + (q.start[2] - q.start[1]);
      q.end[3] = q.end[2] + (q.end[2] - q.end[1]);
    }
    return q;
  }

  bool coin() { return std::bernoulli_distribution(0.5)(random_); }
  PairKind kind() { return coin() ? PairKind::VertexFace : PairKind::EdgeEdge; }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }

 private:
  int pick() { return std::uniform_int_distribution<int>(0, 3)(random_); }
  Vector3d vector(double extent) {
    return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
  }
  std::mt19937 random_;
};

// The block verdicts equal the reference's on every query, with every instruction set this CPU runs; returns how many
// were culled.
int check_same_verdicts(const std::vector<ccd::CcdQuery>& queries, double thickness, bool normals) {
  const ccd::CcdSettings settings{thickness};
  const ccd::ProjectionFilterOptions options{normals};
  int count = 0;
  for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
    std::vector<std::uint8_t> culled;
    ccd::detail::projection_filter_queries(queries, settings, options, culled, isa);
    REQUIRE(culled.size() == queries.size());
    count = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      INFO("query " << i << " thickness " << thickness << " normals " << normals << " isa " << clothcd::simd_level_name(isa));
      CHECK(static_cast<bool>(culled[i]) == ccd::projection_filter_culls(queries[i], settings, options));
      count += culled[i];
    }
  }
  return count;
}

}  // namespace

TEST_CASE("block projection filter: the per-pair filter's verdicts on random and resting pairs", "[ccd][filters]") {
  PairMaker maker(77);
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 3000; ++i) {
    const PairKind kind = maker.kind();
    switch (i % 3) {
      case 0: queries.push_back(maker.random_pair(kind, 1.0, 0.3)); break;
      case 1: queries.push_back(maker.random_pair(kind, 0.05, 0.01)); break;
      default: queries.push_back(maker.resting_pair(kind, 0.004 * maker.uniform(0.5, 2.0))); break;
    }
  }
  for (const double thickness : {0.0, 0.004, 0.05}) {
    for (const bool normals : {false, true}) {
      const int culled = check_same_verdicts(queries, thickness, normals);
      CHECK(culled > 300);  // the filter is at work
    }
  }
}

TEST_CASE("block projection filter: the per-pair filter's verdicts on degenerate pairs", "[ccd][filters]") {
  PairMaker maker(78);
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 2000; ++i) queries.push_back(maker.degenerate_pair(maker.kind()));
  for (const double thickness : {0.0, 0.1}) {
    for (const bool normals : {false, true}) check_same_verdicts(queries, thickness, normals);
  }
}

TEST_CASE("block projection filter: partly filled and mixed-kind blocks", "[ccd][filters]") {
  PairMaker maker(79);
  for (const int n : {1, 2, 15, 16, 17, 31, 33, 50}) {
    std::vector<ccd::CcdQuery> queries;
    for (int i = 0; i < n; ++i) {
      // Runs of one kind of varying length, so blocks break at kind changes as well as when full.
      const PairKind kind = (i / 3) % 2 ? PairKind::EdgeEdge : PairKind::VertexFace;
      queries.push_back(maker.random_pair(kind, 0.1, 0.02));
    }
    check_same_verdicts(queries, 0.004, true);
  }
}

TEST_CASE("block projection filter never drops a pair that comes within the thickness", "[ccd][filters]") {
  PairMaker maker(80);
  const double thickness = 0.004;
  const ccd::CcdSettings settings{thickness};
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 1500; ++i) {
    queries.push_back(maker.resting_pair(maker.kind(), thickness * maker.uniform(0.2, 1.5)));
  }
  for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
    std::vector<std::uint8_t> culled;
    ccd::detail::projection_filter_queries(queries, settings, ccd::ProjectionFilterOptions{true}, culled, isa);
    int within = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      INFO("query " << i << " isa " << clothcd::simd_level_name(isa));
      if (culled[i]) CHECK(ccd::continuous_collision(queries[i], settings).state != ccd::CcdState::Hit);
      if (i % 5 == 0 && clothcd::test::sampled_min_distance(queries[i], 20, 32) <= thickness) {
        ++within;
        CHECK_FALSE(culled[i]);
      }
    }
    CHECK(within > 50);
  }
}

TEST_CASE("block projection filter keeps pairs with huge or tiny coordinates", "[ccd][filters]") {
  PairMaker maker(81);
  std::vector<ccd::CcdQuery> huge, tiny;
  for (int i = 0; i < 64; ++i) {
    ccd::CcdQuery q = maker.random_pair(maker.kind(), 1.0, 0.1);
    ccd::CcdQuery big = q, small = q;
    for (int k = 0; k < 4; ++k) {
      big.start[k] *= 0x1p400;  // beyond 1e100: never culled
      big.end[k] *= 0x1p400;
      small.start[k] *= 0x1p-600;  // normals underflow: only the fixed directions can cull
      small.end[k] *= 0x1p-600;
    }
    huge.push_back(big);
    tiny.push_back(small);
  }
  const ccd::ProjectionFilterOptions normals{true};
  for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
    INFO("isa " << clothcd::simd_level_name(isa));
    std::vector<std::uint8_t> culled;
    ccd::detail::projection_filter_queries(huge, ccd::CcdSettings{0.0}, normals, culled, isa);
    for (const std::uint8_t c : culled) CHECK(c == 0);
    ccd::detail::projection_filter_queries(tiny, ccd::CcdSettings{0.0}, normals, culled, isa);
    int culled_by_fixed = 0, culled_by_block = 0;
    for (std::size_t i = 0; i < tiny.size(); ++i) {
      // The fixed directions alone decide here, as the per-pair filter without normals does (or with them it culls
      // more).
      const bool fixed = ccd::projection_filter_culls(tiny[i], ccd::CcdSettings{0.0});
      culled_by_fixed += fixed;
      culled_by_block += culled[i];
      if (fixed) CHECK(culled[i] == 1);
      if (culled[i]) CHECK(ccd::projection_filter_culls(tiny[i], ccd::CcdSettings{0.0}, normals));
    }
    // Most of these scattered pairs are separated along a fixed direction: the checks above are not vacuous.
    CHECK(culled_by_fixed > 32);
    CHECK(culled_by_block >= culled_by_fixed);
  }
}

TEST_CASE("block projection filter: the Normals pass and the AfterNormals pass together cull what All culls",
          "[ccd][filters]") {
  using ccd::detail::BlockPass;
  PairMaker maker(82);
  const ccd::ProjectionFilterOptions normals{true};
  int only_normals = 0, only_after = 0;
  for (const double thickness : {0.0, 0.004}) {
    const ccd::CcdSettings settings{thickness};
    for (int b = 0; b < 200; ++b) {
      ccd::PairLanes block;
      block.kind = maker.kind();
      block.count = 1 + b % ccd::PairLanes::kLanes;
      for (int lane = 0; lane < block.count; ++lane) {
        block.set(lane, lane % 3 == 0 ? maker.degenerate_pair(block.kind)
                        : lane % 3 == 1 ? maker.resting_pair(block.kind, thickness * maker.uniform(0.5, 3.0) + 1e-3)
                                        : maker.random_pair(block.kind, 0.05, 0.01));
      }
      block.pad_unused();
      for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
        std::uint8_t all[ccd::PairLanes::kLanes], first[ccd::PairLanes::kLanes],
            second[ccd::PairLanes::kLanes];
        ccd::detail::projection_filter_block(block, settings, normals, all, isa, BlockPass::All);
        ccd::detail::projection_filter_block(block, settings, normals, first, isa, BlockPass::Normals);
        ccd::detail::projection_filter_block(block, settings, normals, second, isa, BlockPass::AfterNormals);
        for (int lane = 0; lane < block.count; ++lane) {
          INFO("block " << b << " lane " << lane << " isa " << clothcd::simd_level_name(isa));
          CHECK(static_cast<bool>(all[lane]) == (first[lane] || second[lane]));
          only_normals += first[lane] && !second[lane];
          only_after += second[lane] && !first[lane];
        }
      }
    }
  }
  // Each pass culls pairs the other does not (so neither is a no-op).
  CHECK(only_normals > 0);
  CHECK(only_after > 0);
}

TEST_CASE("block projection filter keeps pairs with a NaN or infinite coordinate", "[ccd][filters]") {
  PairMaker maker(83);
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 64; ++i) {
    ccd::CcdQuery q = maker.random_pair(maker.kind(), 1.0, 0.1);  // far apart: culled when finite
    const double bad = i % 2 ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
    (i % 4 < 2 ? q.start : q.end)[i % 4][i % 3] = bad;
    queries.push_back(q);
  }
  for (const bool normals : {false, true}) {
    for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
      INFO("isa " << clothcd::simd_level_name(isa) << " normals " << normals);
      std::vector<std::uint8_t> culled;
      ccd::detail::projection_filter_queries(queries, ccd::CcdSettings{0.004}, ccd::ProjectionFilterOptions{normals},
                                             culled, isa);
      for (const std::uint8_t c : culled) CHECK(c == 0);
    }
  }
}
