// The rounding of the swept boxes' growth: a coordinate minus (plus) half the thickness is rounded to nearest, so the
// box moves it outwards. Checked exactly, in rationals, on decimal coordinates and thicknesses at every magnitude
// (where x - h/2 is rarely a double): every box holds [min - h/2, max + h/2] of its vertex's two positions, and is
// no more than a few units in the last place larger.
#include <catch2/catch.hpp>

#include <gmpxx.h>

#include <cmath>
#include <random>

#include "broadphase/swept_boxes.hpp"

TEST_CASE("swept boxes hold each position grown by exactly half the thickness, rounded outwards",
          "[broadphase][boxes]") {
  std::mt19937_64 rng(2611);
  std::uniform_int_distribution<long long> digits(-99999, 99999);
  int rounded_inwards_to_nearest = 0;  // cases where rounding to nearest alone would have lost the growth
  for (int exponent = -3; exponent <= 3; ++exponent) {
    const double divisor = std::pow(10.0, 5 - exponent);  // five decimal digits of the magnitude 10^exponent
    for (const double offset : {0.0, 2.7, -1300.0}) {
      const int n = 200;
      clothcd::Vertices start(n, 3), end(n, 3);
      for (int v = 0; v < n; ++v) {
        for (int c = 0; c < 3; ++c) {
          const double base = offset * std::pow(10.0, exponent);
          start(v, c) = base + static_cast<double>(digits(rng)) / divisor;
          end(v, c) = base + static_cast<double>(digits(rng)) / divisor;
        }
      }
      for (const double thickness : {static_cast<double>(std::llabs(digits(rng)) + 1) / divisor, 0.003}) {
        clothcd::broadphase::SweptBoxes boxes;
        clothcd::broadphase::compute_swept_vertex_boxes(start, end, thickness, boxes);
        REQUIRE(boxes.vertices.size() == static_cast<std::size_t>(n));
        const mpq_class half = mpq_class(thickness) / 2;
        for (int v = 0; v < n; ++v) {
          for (int c = 0; c < 3; ++c) {
            INFO("magnitude 1e" << exponent << " offset " << offset << " thickness " << thickness << " vertex " << v);
            const mpq_class low = mpq_class(std::min(start(v, c), end(v, c))) - half;
            const mpq_class high = mpq_class(std::max(start(v, c), end(v, c))) + half;
            const double box_min = boxes.vertices[static_cast<std::size_t>(v)].min[c];
            const double box_max = boxes.vertices[static_cast<std::size_t>(v)].max[c];
            CHECK(mpq_class(box_min) <= low);
            CHECK(mpq_class(box_max) >= high);
            // Tight: within four units in the last place of the exact bounds.
            CHECK(mpq_class(box_min) >= low - 4 * mpq_class(std::abs(box_min) * 0x1p-52 + 0x1p-1074));
            CHECK(mpq_class(box_max) <= high + 4 * mpq_class(std::abs(box_max) * 0x1p-52 + 0x1p-1074));
            const double nearest_low = std::min(start(v, c), end(v, c)) - 0.5 * thickness;
            rounded_inwards_to_nearest += mpq_class(nearest_low) > low;
          }
        }
      }
    }
  }
  CHECK(rounded_inwards_to_nearest > 100);  // the cases the outward rounding exists for are there
}

TEST_CASE("a window's boxes hold the exact positions at its ends, rounded outwards", "[broadphase][boxes]") {
  // Random coordinates from subnormal to 2^60, windows [from, to] of random dyadic ends: the exact rational position
  // x0 + t (x1 - x0) at both ends, grown by half the thickness, lies in the box (linear motion between them then
  // does too), and the box is no more than a few units in the last place of the larger end larger.
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-1070, 60), numerator(0, 1023);
  int inexact_ends = 0;  // window ends whose rounded position differs from the exact one
  for (int round = 0; round < 400; ++round) {
    const int n = 16;
    clothcd::Vertices start(n, 3), end(n, 3);
    const double scale = std::ldexp(1.0, exponent(rng));
    for (int v = 0; v < n; ++v) {
      for (int c = 0; c < 3; ++c) {
        start(v, c) = scale * unit(rng);
        end(v, c) = v % 5 == 0 ? start(v, c) : scale * unit(rng);  // some coordinates do not move
      }
    }
    const int a = numerator(rng), b = numerator(rng);
    if (a == b) continue;
    const double from = std::ldexp(static_cast<double>(std::min(a, b)), -10);
    const double to = std::ldexp(static_cast<double>(std::max(a, b) + 1), -10);
    const double thickness = round % 3 == 0 ? 0.0 : scale * std::fabs(unit(rng));
    clothcd::broadphase::SweptBoxes boxes;
    clothcd::broadphase::compute_part_vertex_boxes(start, end, from, to, thickness, boxes);
    REQUIRE(boxes.vertices.size() == static_cast<std::size_t>(n));
    const mpq_class half = mpq_class(thickness) / 2;
    for (int v = 0; v < n; ++v) {
      for (int c = 0; c < 3; ++c) {
        INFO("round " << round << " vertex " << v << " window [" << from << ", " << to << "]");
        const mpq_class x0(start(v, c)), x1(end(v, c));
        const mpq_class at_from = x0 + mpq_class(from) * (x1 - x0), at_to = x0 + mpq_class(to) * (x1 - x0);
        const clothcd::broadphase::FlatBox& box = boxes.vertices[static_cast<std::size_t>(v)];
        CHECK(mpq_class(box.min[c]) <= (at_from < at_to ? at_from : at_to) - half);
        CHECK(mpq_class(box.max[c]) >= (at_from < at_to ? at_to : at_from) + half);
        const double magnitude = std::max(std::fabs(start(v, c)), std::fabs(end(v, c))) + thickness;
        const mpq_class loose(magnitude * 0x1p-47 + 0x1p-1070);
        CHECK(mpq_class(box.min[c]) >= (at_from < at_to ? at_from : at_to) - half - loose);
        CHECK(mpq_class(box.max[c]) <= (at_from < at_to ? at_to : at_from) + half + loose);
        inexact_ends += mpq_class(start(v, c) + to * (end(v, c) - start(v, c))) != at_to;
      }
    }
  }
  CHECK(inexact_ends > 1000);  // the rounding the slack covers does occur
}
