// Packed primitive data: the single-precision box copies contain the double boxes they come from at every magnitude
// (so a four- or eight-lane pre-selection never separates overlapping boxes), padding never overlaps, and the
// vertex-index lanes agree with a scalar comparison.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "broadphase/leaf_pairs.hpp"
#include "broadphase/packed_boxes.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

namespace {

using clothcd::broadphase::FlatBox;
using clothcd::broadphase::pack_box;
using clothcd::broadphase::PackedBoxes;
using clothcd::broadphase::PackedVertexIds;
using clothcd::SimdLevel;
using clothcd::broadphase::detail::packed_lane_width;

// Bits of box j's group of lanes overlapping `q` at `level`.
unsigned overlap_bits(const PackedBoxes& packed, SimdLevel level, int j, const clothcd::broadphase::PackedBox& q) {
  return clothcd::broadphase::detail::packed_overlap_bits(level, packed, j, q);
}

// Bits of primitive j's group of lanes using vertex v, or for edges (per = 2) v or w (per = 3: faces), at `level`.
unsigned uses_bits(const PackedVertexIds& packed, int per, SimdLevel level, int j, int v, int w) {
  return per == 2 ? clothcd::broadphase::detail::packed_edge_uses_bits(level, packed, j, v, w)
                  : clothcd::broadphase::detail::packed_face_uses_bits(level, packed, j, v);
}

// A double of random sign, mantissa and binary exponent in [min_exp, max_exp].
double random_double(std::mt19937_64& rng, int min_exp, int max_exp) {
  std::uniform_real_distribution<double> mantissa(0.5, 1.0);
  std::uniform_int_distribution<int> exponent(min_exp, max_exp);
  const double x = std::ldexp(mantissa(rng), exponent(rng));
  return rng() % 2 == 0 ? x : -x;
}

FlatBox box_around(double x, double y, double z, double half) {
  return FlatBox{{x - half, y - half, z - half}, {x + half, y + half, z + half}};
}

}  // namespace

TEST_CASE("packed boxes contain the double boxes at every magnitude", "[broadphase][packed]") {
  std::mt19937_64 rng(41);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values{0.0, -0.0, inf, -inf, 1e39, -1e39, 3.4028234e38, -3.4028234e38, 1e-45, -1e-45,
                             std::numeric_limits<double>::denorm_min(), 1.0, -1.0,
                             1e38, -1e38, 9.99999e37, -9.99999e37, 1.00001e38, -1.00001e38, 1e-30, -1e-30};
  for (int i = 0; i < 200000; ++i) values.push_back(random_double(rng, -1074, 1023));
  for (int i = 0; i < 200000; ++i) values.push_back(random_double(rng, -30, 30));
  for (const double x : values) {
    const clothcd::broadphase::PackedBox p = pack_box(FlatBox{{x, x, x}, {x, x, x}});
    for (int k = 0; k < 3; ++k) {
      REQUIRE(static_cast<double>(p.lo[k]) <= x);
      REQUIRE(static_cast<double>(p.hi[k]) >= x);
    }
  }
}

TEST_CASE("packed rows (at every SIMD level) hold exactly pack_box's floats", "[broadphase][packed]") {
  std::mt19937_64 rng(53);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> special{0.0, -0.0, inf, -inf, nan, 1e38, -1e38, 9.99999e37, -9.99999e37, 1e39, -1e39,
                                    std::numeric_limits<double>::denorm_min(), -1e-300, 1e-30, -1e-30};
  for (const int count : {1, 3, 4, 5, 8, 13, 1001}) {
    std::vector<FlatBox> boxes(count);
    for (FlatBox& b : boxes) {
      for (int k = 0; k < 3; ++k) {
        const bool pick_special = rng() % 4 == 0;
        b.min[k] = pick_special ? special[rng() % special.size()] : random_double(rng, -1074, 1023);
        b.max[k] = pick_special ? special[rng() % special.size()] : random_double(rng, -40, 40);
      }
    }
    for (const SimdLevel level : clothcd::cpu_simd_levels()) {
      clothcd::test::SimdLimit capped(level);
      PackedBoxes packed;
      packed.assign(boxes);
      for (int j = 0; j < count; ++j) {
        const clothcd::broadphase::PackedBox row = packed.at(j), single = pack_box(boxes[j]);
        REQUIRE(std::memcmp(&row, &single, sizeof row) == 0);
      }
    }
  }
}

TEST_CASE("packed overlap lanes (at every SIMD level) never separate overlapping boxes and ignore padding", "[broadphase][packed]") {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> count(1, 13);
  for (int trial = 0; trial < 3000; ++trial) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 200) - 100);
    std::vector<FlatBox> boxes(count(rng));
    for (FlatBox& b : boxes) b = box_around(scale * unit(rng), scale * unit(rng), scale * unit(rng), scale * 0.1);
    // Queries touching a box exactly, one ulp apart from it, or anywhere.
    FlatBox q = box_around(scale * unit(rng), scale * unit(rng), scale * unit(rng), scale * 0.2 * (unit(rng) + 1));
    const FlatBox& target = boxes[rng() % boxes.size()];
    if (trial % 3 == 0) q.min[0] = target.max[0];
    if (trial % 3 == 1) q.min[0] = std::nextafter(target.max[0], 2 * std::abs(target.max[0]) + 1);
    PackedBoxes packed;
    packed.assign(boxes);
    REQUIRE(packed.size() == static_cast<int>(boxes.size()));
    const auto packed_q = pack_box(q);
    for (const SimdLevel level : clothcd::cpu_simd_levels()) {
      const int width = packed_lane_width(level);
      int passes = 0, overlaps = 0;
      for (int j = 0; j < packed.size(); j += width) {
        const unsigned bits = overlap_bits(packed, level, j, packed_q);
        for (int k = 0; k < width; ++k) {
          const bool lane = ((bits >> k) & 1u) != 0;
          if (j + k >= packed.size()) {
            REQUIRE_FALSE(lane);
            continue;
          }
          if (boxes[j + k].overlaps(q)) {
            REQUIRE(lane);
            ++overlaps;
          }
          passes += lane ? 1 : 0;
        }
      }
      REQUIRE(passes >= overlaps);
    }
  }
}

TEST_CASE("packed vertex-index lanes agree with a scalar comparison", "[broadphase][packed]") {
  std::mt19937_64 rng(47);
  std::uniform_int_distribution<int> vertex(0, 9);
  for (const int per : {2, 3}) {
    std::vector<int> ids(per * 11);
    for (int& id : ids) id = vertex(rng);
    PackedVertexIds packed;
    packed.assign(ids, per);
    const int primitives = static_cast<int>(ids.size()) / per;
    for (const SimdLevel level : clothcd::cpu_simd_levels()) {
      const int width = packed_lane_width(level);
      for (int v = 0; v < 10; ++v) {
        const int w = per == 2 ? (v * 7 + 3) % 10 : v;  // edges: a second vertex, sometimes v itself
        for (int j = 0; j < primitives; ++j) {
          const unsigned bits = uses_bits(packed, per, level, j, v, w);
          for (int k = 0; k < width; ++k) {
            bool uses = false;
            if (j + k < primitives) {
              for (int r = 0; r < per; ++r) uses = uses || ids[per * (j + k) + r] == v || ids[per * (j + k) + r] == w;
            }
            REQUIRE((((bits >> k) & 1u) != 0) == uses);
          }
        }
      }
    }
  }
}
