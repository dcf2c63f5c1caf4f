// The narrow phase behind a filter (ccd::continuous_collision_after_filter) skips the filter tests it would
// repeat; on every query the filter passes it must answer exactly like continuous_collision, the reference.
#include <catch2/catch.hpp>

#include <random>

#include "ccd_test_support.hpp"

using namespace clothcd;
using clothcd::test::make_query;
using Eigen::Vector3d;

namespace {

// Queries around contact: random points in a small cube with random motions, plus degenerate ones (no motion,
// coincident vertices, everything in one plane).
std::vector<ccd::CcdQuery> test_queries(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto point = [&](double scale) -> Vector3d {
    const Vector3d p(u(rng), u(rng), u(rng));
    return scale * p;
  };
  std::vector<ccd::CcdQuery> queries;
  for (int i = 0; i < 240; ++i) {
    const PairKind kind = i % 2 == 0 ? PairKind::VertexFace : PairKind::EdgeEdge;
    std::array<Vector3d, 4> start, end;
    for (int k = 0; k < 4; ++k) {
      start[k] = point(0.05);
      end[k] = start[k] + point(i % 5 == 0 ? 0.0 : 0.04);  // every fifth query does not move
    }
    if (i % 7 == 0) start[1] = start[0], end[1] = end[0];  // coincident vertices
    if (i % 11 == 0) {
      for (int k = 0; k < 4; ++k) start[k].z() = end[k].z() = 0.0;  // flat: all in one plane
    }
    queries.push_back(make_query(kind, start, end));
  }
  return queries;
}

void check_same(const ccd::CcdResult& a, const ccd::CcdResult& b) {
  CHECK(a.hit == b.hit);
  CHECK(a.state == b.state);
  CHECK(a.toi == b.toi);
  CHECK(a.parameters == b.parameters);
  CHECK(a.normal == b.normal);
  CHECK(a.exact_fallback == b.exact_fallback);
}

}  // namespace

TEST_CASE("CCD behind a filter answers like the full CCD on every pair the filter passes", "[ccd][after-filter]") {
  const double thickness = GENERATE(0.0, 0.004);
  const bool decide_exactly = GENERATE(false, true);
  const ccd::CcdFilter filter = GENERATE(ccd::CcdFilter::None, ccd::CcdFilter::NonPenetration,
                                         ccd::CcdFilter::Projection, ccd::CcdFilter::Combined);
  std::mt19937 rng(2024);
  const ccd::CcdSettings settings{thickness, decide_exactly};
  int passed = 0, hits = 0;
  for (const ccd::CcdQuery& query : test_queries(rng)) {
    if (ccd::filter_culls(filter, query, settings)) continue;
    ++passed;
    const ccd::CcdResult reference = ccd::continuous_collision(query, settings);
    hits += reference.hit ? 1 : 0;
    check_same(ccd::continuous_collision_after_filter(query, settings, filter), reference);
  }
  // The set must exercise both answers.
  CHECK(passed > 50);
  CHECK(hits > 10);
  CHECK(hits < passed);
}
