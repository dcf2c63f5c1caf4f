#pragma once
// A cube root within a few units in the last place, written as straight-line double arithmetic, selects and bit
// operations only, so that the compiler vectorizes a loop of them (the C library's cbrt is a call per value, and was
// a third of the feature time; its users are built with -fno-trapping-math, which lets the selects become vector
// blends). The pair features use it in the per-pair and in the block code alike. Internal.

#include <cmath>
#include <cstdint>
#include <cstring>

namespace clothcd::learning::detail {

/// The double with the given bits.
[[gnu::always_inline]] inline double double_from_bits(std::uint64_t bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

/// The bits of a double.
[[gnu::always_inline]] inline std::uint64_t bits_of(double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  return bits;
}

/// The real cube root of a (odd: cube_root(-a) = -cube_root(a)); zeros, infinities and NaN give themselves.
[[gnu::always_inline]] inline double cube_root(double a) {
  constexpr double kRound = 0x1p52;  // adding and subtracting it rounds a value in [0, 2^51) to an integer
  const double x = std::abs(a);
  // Tiny and subnormal inputs are first scaled by 2^108 (cube root 2^36) into the normal range.
  const bool tiny = x < 0x1p-900;
  const std::uint64_t bits = bits_of(tiny ? x * 0x1p108 : x);
  // x = m 2^e with m in [1, 2); e from the exponent field as a double (2^52 + field, exactly, minus 2^52).
  const double e = (double_from_bits((bits >> 52) | bits_of(kRound)) - kRound) - 1023.0;
  const double m = double_from_bits((bits & 0x000FFFFFFFFFFFFFull) | bits_of(1.0));
  // e = 3 q + r with r in {0, 1, 2}: (e + 3072) / 3 lies 0, 1/3 or 2/3 above an integer, so minus 1/3 it rounds to
  // that integer.
  const double q = ((((e + 3072.0) / 3.0 - 1.0 / 3.0) + kRound) - kRound) - 1024.0;
  const double r = e - 3.0 * q;
  const double z = m * (1.0 + r * (1.0 + 0.5 * (r - 1.0)));  // m 2^r (exact) in [1, 8); the root is cbrt(z) 2^q
  // A cubic fit of the root on [1, 8] (relative error below 1.4%), two Halley steps (each cubes the error), then one
  // Newton step, whose small correction rounds to within about an ulp.
  double y = 0.70906 + z * (0.340075 + z * (-0.0375077 + z * 0.00191743));
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y = y * (y3 + 2.0 * z) / (2.0 * y3 + z);
  }
  y = y - (y * y * y - z) / (3.0 * y * y);
  // 2^q from its exponent field (q + 1023 in [682, 1364]), then the scaling undone; both products are exact.
  const double power = double_from_bits((bits_of(q + 1023.0 + kRound) & 0x7FFull) << 52);
  const double root = y * power * (tiny ? 0x1p-36 : 1.0);
  return (x == 0.0) | !(x <= 0x1.fffffffffffffp1023) ? a : std::copysign(root, a);
}

}  // namespace clothcd::learning::detail
