#pragma once
// Private: closed intervals of doubles with outward rounding, for the safe floating-point CCD. Every operation widens
// its rounded-to-nearest result by more than one rounding error (2^-51 relative plus 2^-1070 absolute for underflow),
// so the true real result of the operation on any real numbers inside the operands lies inside the result.
#include <algorithm>
#include <cmath>

namespace clothcd::ccd::detail {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

inline double round_down(double x) {
  return x - (std::fabs(x) * 0x1p-51 + 0x1p-1070);
}
inline double round_up(double x) {
  return x + (std::fabs(x) * 0x1p-51 + 0x1p-1070);
}

inline Interval exact(double x) {
  return {x, x};
}
inline Interval hull(const Interval& a, const Interval& b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval operator+(const Interval& a, const Interval& b) {
  return {round_down(a.lo + b.lo), round_up(a.hi + b.hi)};
}
inline Interval operator-(const Interval& a, const Interval& b) {
  return {round_down(a.lo - b.hi), round_up(a.hi - b.lo)};
}
inline Interval operator*(const Interval& a, const Interval& b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {round_down(std::min(std::min(p[0], p[1]), std::min(p[2], p[3]))),
          round_up(std::max(std::max(p[0], p[1]), std::max(p[2], p[3])))};
}

/// Sign certain under the enclosure: 1 or -1, else 0 (zero inside, or NaN bounds).
inline int certain_sign(const Interval& a) {
  return a.lo > 0.0 ? 1 : (a.hi < 0.0 ? -1 : 0);
}

}  // namespace clothcd::ccd::detail
