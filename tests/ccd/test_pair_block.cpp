// The pair block of the detector's pipeline (ccd/pair_block.hpp): pairs keep their vertices, tags and positions
// through pushes, swaps and compaction, and cull_pairs keeps exactly the pairs the references keep: the block
// projection filter over a vector of queries (projection_filter_queries, itself checked against the per-pair filter)
// and the per-pair non-penetration filter, for every culling mode, on seeded random pairs of every block fill.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "ccd/pair_block.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "support/simd_level.hpp"

namespace {

using clothcd::PairKind;
using clothcd::VertexRef;
namespace ccd = clothcd::ccd;
using ccd::PairBlock;

// Pairs of one kind near each other, moving a little: some collide, many are culled, some are not.
std::vector<ccd::CcdQuery> random_pairs(PairKind kind, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> place(-1.0, 1.0), move(-0.3, 0.3);
  std::vector<ccd::CcdQuery> pairs(static_cast<std::size_t>(count));
  for (ccd::CcdQuery& q : pairs) {
    q.kind = kind;
    for (int k = 0; k < 4; ++k) {
      q.start[k] = Eigen::Vector3d(place(rng), place(rng), place(rng));
      q.end[k] = q.start[k] + Eigen::Vector3d(move(rng), move(rng), move(rng));
    }
  }
  return pairs;
}

// Fills `block` with `pairs`, pair i tagged i and made of vertices 4i .. 4i + 3 of body i % 3.
void fill(PairBlock& block, const std::vector<ccd::CcdQuery>& pairs) {
  block.reset(pairs.front().kind);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const int body = static_cast<int>(i % 3), v = 4 * static_cast<int>(i);
    std::array<const double*, 4> start, end;
    for (int k = 0; k < 4; ++k) {
      start[k] = pairs[i].start[k].data();
      end[k] = pairs[i].end[k].data();
    }
    block.push({VertexRef{body, v}, VertexRef{body, v + 1}, VertexRef{body, v + 2}, VertexRef{body, v + 3}}, i, start,
               end);
  }
}

// Pair i of `block` is pairs[tag] with the vertices fill() gave it.
void check_pair(const PairBlock& block, int i, const std::vector<ccd::CcdQuery>& pairs) {
  const std::size_t tag = block.tag(i);
  REQUIRE(tag < pairs.size());
  const ccd::CcdQuery q = block.query(i);
  CHECK(q.kind == pairs[tag].kind);
  for (int k = 0; k < 4; ++k) {
    CHECK(q.start[k] == pairs[tag].start[k]);
    CHECK(q.end[k] == pairs[tag].end[k]);
    CHECK(block.vertices(i)[static_cast<std::size_t>(k)].vertex == 4 * static_cast<int>(tag) + k);
    CHECK(block.vertices(i)[static_cast<std::size_t>(k)].body == static_cast<int>(tag % 3));
  }
}

}  // namespace

TEST_CASE("a pair block keeps each pair's vertices, tag and positions through swaps and compaction", "[ccd][block]") {
  const int count = GENERATE(1, 15, 16, 17, 40);
  const std::vector<ccd::CcdQuery> pairs = random_pairs(PairKind::EdgeEdge, count, 7);
  PairBlock block(40);
  CHECK(block.capacity() == 48);  // whole lane groups
  fill(block, pairs);
  REQUIRE(block.size() == count);
  CHECK(block.full() == (count == 48));
  for (int i = 0; i < count; ++i) check_pair(block, i, pairs);
  block.swap_pairs(0, count - 1);
  check_pair(block, 0, pairs);
  CHECK(block.tag(0) == static_cast<std::uint64_t>(count - 1));
  block.swap_pairs(0, count - 1);
  // Keep every third pair of the first half; the second half moves down behind them, in order.
  const int half = count / 2;
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(half));
  int expected = 0;
  for (int i = 0; i < half; ++i) {
    keep[static_cast<std::size_t>(i)] = i % 3 == 0;
    expected += i % 3 == 0;
  }
  CHECK(block.compact(half, keep.data()) == expected);
  REQUIRE(block.size() == expected + count - half);
  std::vector<std::uint64_t> tags;
  for (int i = 0; i < half; ++i) {
    if (i % 3 == 0) tags.push_back(static_cast<std::uint64_t>(i));
  }
  for (int i = half; i < count; ++i) tags.push_back(static_cast<std::uint64_t>(i));
  for (int i = 0; i < block.size(); ++i) {
    CHECK(block.tag(i) == tags[static_cast<std::size_t>(i)]);
    check_pair(block, i, pairs);
  }
}

TEST_CASE("a pair block of a bad capacity is refused", "[ccd][block][errors]") {
  CHECK_THROWS_AS(PairBlock(0), std::invalid_argument);
  CHECK_THROWS_AS(PairBlock((1 << 20) + 1), std::invalid_argument);
}

TEST_CASE("cull_pairs keeps exactly what the reference filters keep", "[ccd][block]") {
  const PairKind kind = GENERATE(PairKind::VertexFace, PairKind::EdgeEdge);
  const ccd::CcdFilter filter = GENERATE(ccd::CcdFilter::None, ccd::CcdFilter::NonPenetration,
                                         ccd::CcdFilter::Projection, ccd::CcdFilter::Combined);
  const bool normals = GENERATE(false, true);
  const double thickness = GENERATE(0.0, 0.05);
  const int count = GENERATE(1, 16, 33, 200);
  const std::vector<ccd::CcdQuery> pairs = random_pairs(kind, count, static_cast<unsigned>(count) + 11);
  const ccd::CcdSettings settings{thickness};
  const ccd::ProjectionFilterOptions options{normals};

  std::vector<std::uint8_t> projection;
  ccd::detail::projection_filter_queries(pairs, settings, options, projection);
  std::vector<std::uint64_t> expected;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const bool projected = (filter == ccd::CcdFilter::Projection || filter == ccd::CcdFilter::Combined) &&
                           projection[i] != 0;
    const bool nonpenetration =
        (filter == ccd::CcdFilter::NonPenetration || filter == ccd::CcdFilter::Combined) &&
        ccd::nonpenetration_filter_culls(pairs[i], settings);
    if (!projected && !nonpenetration) expected.push_back(i);
  }
  for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
    PairBlock block(200);
    fill(block, pairs);
    std::vector<std::uint8_t> scratch;
    const int kept = ccd::detail::cull_pairs(block, count, filter, settings, options, isa, scratch);
    REQUIRE(kept == static_cast<int>(expected.size()));
    REQUIRE(block.size() == kept);
    for (int i = 0; i < kept; ++i) {
      CHECK(block.tag(i) == expected[static_cast<std::size_t>(i)]);
      check_pair(block, i, pairs);
    }
  }
  // Safety: no pair that collides is culled.
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (ccd::continuous_collision(pairs[i], settings).hit) {
      CHECK(std::find(expected.begin(), expected.end(), i) != expected.end());
    }
  }
  if (count == 200 && filter == ccd::CcdFilter::Combined) CHECK(expected.size() < pairs.size());
}
