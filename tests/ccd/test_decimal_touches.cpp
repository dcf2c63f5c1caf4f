// Exact and near touches with decimal coordinates (decimal_touches.hpp) against the exact reference: the CCD, every
// per-pair filter, the block filter on every instruction set and the network culler never miss or cull a pair the
// reference calls a collision, at thickness 0 and at small thicknesses; the exact mode agrees with the reference on
// every pair. One test case (the labelled set is built once per process), a section per path. Failures are counted
// and reported with the first few pairs, so that a weakened bound shows as "N culled" rather than N assertions.
#include <catch2/catch.hpp>

#include <array>
#include <map>
#include <sstream>

#include "ccd/ccd_test_support.hpp"
#include "ccd/decimal_touches.hpp"
#include "ccd/projection_block.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "support/simd_level.hpp"

using clothcd::test::decimal_thick_touches;
using clothcd::test::decimal_touches;
using clothcd::test::LabelledTouch;
using clothcd::test::ThickTouch;
namespace ccd = clothcd::ccd;

namespace {

std::string describe(const ccd::CcdQuery& q) {
  std::ostringstream out;
  out.precision(17);
  out << (q.kind == clothcd::PairKind::VertexFace ? "vertex-face" : "edge-edge") << " start";
  for (const auto& p : q.start) out << " (" << p.transpose() << ")";
  out << " end";
  for (const auto& p : q.end) out << " (" << p.transpose() << ")";
  return out.str();
}

// Wrong answers of one path: how many, and the first few pairs.
class Failures {
 public:
  void add(const ccd::CcdQuery& q, const std::string& what) {
    if (++count_ <= 3) examples_ << what << ": " << describe(q) << "\n";
  }
  int count() const { return count_; }
  std::string examples() const { return examples_.str(); }

 private:
  int count_ = 0;
  std::ostringstream examples_;
};

#define CHECK_NO_FAILURES(failures)   \
  do {                                \
    INFO((failures).examples());      \
    CHECK((failures).count() == 0);   \
  } while (false)

// The thickness-0 collisions by magnitude (each group runs at its magnitude's thicknesses).
std::map<int, std::vector<ccd::CcdQuery>> collisions_by_exponent() {
  std::map<int, std::vector<ccd::CcdQuery>> out;
  for (const LabelledTouch& t : decimal_touches()) {
    if (t.collides) out[t.exponent].push_back(t.query);
  }
  return out;
}

// The thickness collisions by thickness.
std::map<double, std::vector<ccd::CcdQuery>> thick_by_thickness() {
  std::map<double, std::vector<ccd::CcdQuery>> out;
  for (const ThickTouch& t : decimal_thick_touches()) out[t.thickness].push_back(t.query);
  return out;
}

// Every (queries, thickness) group a culling path must keep whole: the thickness-0 collisions at 0 and at their
// magnitude's thicknesses, and the thickness collisions at their own thickness.
template <class Check>
void for_each_group(const Check& check) {
  for (const auto& [exponent, queries] : collisions_by_exponent()) {
    check(queries, 0.0);
    for (const double thickness : clothcd::test::touch_thicknesses(exponent)) check(queries, thickness);
  }
  for (const auto& [thickness, queries] : thick_by_thickness()) check(queries, thickness);
}

}  // namespace

TEST_CASE("decimal touches: exact and near touches with decimal coordinates against the exact reference",
          "[ccd][differential][filters][decimal]") {
  const std::vector<LabelledTouch>& touches = decimal_touches();

  SECTION("thousands of touches at every magnitude, both answers in every family") {
    std::array<int, clothcd::test::kTouchFamilies> hits{}, misses{};
    std::array<int, 7> hits_by_exponent{};
    for (const LabelledTouch& t : touches) {
      (t.collides ? hits : misses)[static_cast<std::size_t>(t.family)]++;
      if (t.collides) hits_by_exponent[static_cast<std::size_t>(t.exponent + 3)]++;
    }
    int total = 0;
    for (std::size_t f = 0; f < hits.size(); ++f) {
      INFO("family " << f << ": " << hits[f] << " collide, " << misses[f] << " miss");
      CHECK(hits[f] > 50);  // both answers: a generator that always (or never) touches proves little
      CHECK(misses[f] > 30);
      total += hits[f];
    }
    CHECK(total > 5000);
    for (const int h : hits_by_exponent) CHECK(h > 500);
    CHECK(decimal_thick_touches().size() > 500);
  }

  SECTION("the CCD never misses a reference collision and its exact mode agrees with the reference") {
    const ccd::CcdSettings exact = clothcd::test::exact_settings();
    Failures exact_mode, fast_mode, thick;
    for (const LabelledTouch& t : touches) {
      if (ccd::continuous_collision(t.query, exact).hit != t.collides) exact_mode.add(t.query, "exact mode differs");
      const ccd::CcdResult fast = ccd::continuous_collision(t.query);
      if (t.collides ? !fast.hit : fast.state == ccd::CcdState::Hit) fast_mode.add(t.query, "default mode wrong");
      if (!t.collides) continue;
      // A pair that touches at thickness 0 comes within every larger thickness.
      for (const double thickness : clothcd::test::touch_thicknesses(t.exponent)) {
        if (!ccd::continuous_collision(t.query, ccd::CcdSettings{thickness}).hit) thick.add(t.query, "thick miss");
      }
    }
    for (const ThickTouch& t : decimal_thick_touches()) {
      if (!ccd::continuous_collision(t.query, ccd::CcdSettings{t.thickness}).hit) thick.add(t.query, "thick miss");
    }
    CHECK_NO_FAILURES(exact_mode);
    CHECK_NO_FAILURES(fast_mode);
    CHECK_NO_FAILURES(thick);
  }

  SECTION("no per-pair filter culls a reference collision") {
    Failures nonpenetration, projection, with_normals, combined;
    const ccd::ProjectionFilterOptions normals{true};
    for_each_group([&](const std::vector<ccd::CcdQuery>& queries, double thickness) {
      const ccd::CcdSettings settings{thickness};
      for (const ccd::CcdQuery& q : queries) {
        if (ccd::nonpenetration_filter_culls(q, settings)) nonpenetration.add(q, "thickness " + std::to_string(thickness));
        if (ccd::projection_filter_culls(q, settings)) projection.add(q, "thickness " + std::to_string(thickness));
        if (ccd::projection_filter_culls(q, settings, normals)) with_normals.add(q, "thickness " + std::to_string(thickness));
        if (ccd::combined_filters_cull(q, settings)) combined.add(q, "thickness " + std::to_string(thickness));
      }
    });
    CHECK_NO_FAILURES(nonpenetration);
    CHECK_NO_FAILURES(projection);
    CHECK_NO_FAILURES(with_normals);
    CHECK_NO_FAILURES(combined);
  }

  SECTION("the block projection filter culls no reference collision on any instruction set") {
    for (const clothcd::SimdLevel isa : clothcd::cpu_simd_levels()) {
      for (const bool use_normals : {false, true}) {
        INFO("instruction set " << clothcd::simd_level_name(isa) << ", primitive normals " << use_normals);
        Failures culled_pairs;
        std::vector<std::uint8_t> culled;
        for_each_group([&](const std::vector<ccd::CcdQuery>& queries, double thickness) {
          ccd::detail::projection_filter_queries(queries, ccd::CcdSettings{thickness},
                                                 ccd::ProjectionFilterOptions{use_normals}, culled, isa);
          for (std::size_t i = 0; i < queries.size(); ++i) {
            if (culled[i]) culled_pairs.add(queries[i], "thickness " + std::to_string(thickness));
          }
        });
        CHECK_NO_FAILURES(culled_pairs);
      }
    }
  }

  SECTION("the network culler culls no reference collision, even told to drop every pair") {
    clothcd::learning::NetworkCuller culler;
    for (const bool reckless : {false, true}) {
      if (reckless) culler.set_operating_point({1.0, 1.0});  // drops every pair it is not certain to keep
      for (const bool normals : {false, true}) {
        INFO("reckless " << reckless << ", primitive normals " << normals);
        Failures culled_pairs;
        long dropped_by_network = 0;
        std::vector<std::uint8_t> keep;
        for_each_group([&](const std::vector<ccd::CcdQuery>& queries, double thickness) {
          culler.cull(queries, ccd::CcdSettings{thickness}, false, keep, ccd::ProjectionFilterOptions{normals});
          for (std::size_t i = 0; i < queries.size(); ++i) {
            if (keep[i] != 1) culled_pairs.add(queries[i], "thickness " + std::to_string(thickness));
            dropped_by_network += culler.decisions()[i] == clothcd::learning::PairDecision::Drop;
          }
        });
        CHECK_NO_FAILURES(culled_pairs);
        // Told to drop everything, the network does send these pairs to the filters: the filters alone keep them.
        if (reckless) CHECK(dropped_by_network > 1000);
      }
    }
  }
}
