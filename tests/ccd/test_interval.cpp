// The safe CCD's interval arithmetic: every result encloses the exact result on the operands' endpoints, from huge
// down to subnormal magnitudes, and exact zeros stay exact (no subnormal numbers made out of nothing).
#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <cmath>
#include <random>

#include "ccd/interval.hpp"

using clothcd::ccd::detail::Interval;

namespace {

// A random interval whose endpoints have magnitudes between 2^-1074 and 2^60, zero now and then.
Interval random_interval(std::mt19937& random) {
  std::uniform_int_distribution<int> exponent(-1080, 60), pick(0, 5);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  auto endpoint = [&] { return pick(random) == 0 ? 0.0 : std::ldexp(mantissa(random), exponent(random)); };
  double a = endpoint(), b = pick(random) == 0 ? a : endpoint();
  if (a > b) std::swap(a, b);
  return {a, b};
}

bool encloses(const Interval& r, const mpq_class& value) {
  return mpq_class(r.lo) <= value && value <= mpq_class(r.hi);
}

}  // namespace

TEST_CASE("interval sums, differences and products enclose the exact results", "[ccd][interval]") {
  std::mt19937 random(314159u);
  int underflowing_products = 0;
  for (int i = 0; i < 20000; ++i) {
    const Interval a = random_interval(random), b = random_interval(random);
    const Interval sum = a + b, difference = a - b, product = a * b;
    for (const double x : {a.lo, a.hi}) {
      for (const double y : {b.lo, b.hi}) {
        INFO("a [" << a.lo << ", " << a.hi << "] b [" << b.lo << ", " << b.hi << "] x " << x << " y " << y);
        CHECK(encloses(sum, mpq_class(x) + mpq_class(y)));
        CHECK(encloses(difference, mpq_class(x) - mpq_class(y)));
        const mpq_class exact_product = mpq_class(x) * mpq_class(y);
        CHECK(encloses(product, exact_product));
        if (exact_product != 0 && std::fabs(x * y) < 0x1p-1022) ++underflowing_products;
      }
    }
    // Scaling by a positive constant of the kind the CCD uses (times in the step, 1/2, 2, 3).
    for (const double c : {0.5, 3.0, 0.3125, 0x1p-30}) {
      const Interval s = clothcd::ccd::detail::scaled(a, c);
      CHECK(encloses(s, mpq_class(a.lo) * mpq_class(c)));
      CHECK(encloses(s, mpq_class(a.hi) * mpq_class(c)));
    }
  }
  CHECK(underflowing_products > 1000);  // the generator reaches the underflow range, or the test proves little
}

TEST_CASE("exact zeros stay exact zeros", "[ccd][interval]") {
  const Interval zero{0.0, 0.0}, unit{0.5, 2.0}, straddling{-1.0, 3.0};
  for (const Interval& r : {zero + zero, zero - zero, zero * unit, straddling * zero, zero * zero}) {
    CHECK(r.lo == 0.0);
    CHECK(r.hi == 0.0);
  }
  const Interval from_zero = Interval{0.0, 1.0} * unit;
  CHECK(from_zero.lo == 0.0);
}
