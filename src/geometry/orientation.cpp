// The exact orientation predicates: the filters of geometry/orientation_filter.hpp, their fallbacks on expansions
// (geometry/expansion_orientation.hpp), and the last resort in GMP integers (the coordinates scaled exactly by one
// power of two).
#include "geometry/orientation.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/expansion_orientation.hpp"
#include "geometry/orientation_filter.hpp"

namespace clothcd::geometry {

Orientation orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                     const Eigen::Vector3d& s) {
  return filter::orient3d_exact_sign(p, q, r, s);
}

Orientation orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int drop_axis) {
  return filter::orient2d_exact_sign(p, q, r, drop_axis);
}

int exact_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                   const Eigen::Vector3d& s) {
  const std::optional<int> sign = detail::expansion_orient3d(p, q, r, s);
  return sign ? *sign : gmp_orient3d(p, q, r, s);
}

int exact_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int drop_axis) {
  const std::optional<int> sign = detail::expansion_orient2d(p, q, r, drop_axis);
  return sign ? *sign : gmp_orient2d(p, q, r, drop_axis);
}

namespace {

// The values as integers times one common power of two (a double is a 53-bit integer times a power of two), so that
// the determinants run on GMP integers: their signs are the same, and integers need no canonicalization.
template <int N>
void to_integers(const std::array<double, N>& values, std::array<mpz_class, N>& out) {
  std::array<long, N> mantissa{};
  std::array<int, N> exponent{};
  int smallest = std::numeric_limits<int>::max();
  for (int i = 0; i < N; ++i) {
    if (values[i] == 0.0) continue;
    int e = 0;
    mantissa[i] = static_cast<long>(std::ldexp(std::frexp(values[i], &e), 53));
    exponent[i] = e - 53;
    smallest = std::min(smallest, exponent[i]);
  }
  for (int i = 0; i < N; ++i) {
    out[i] = mantissa[i];
    if (mantissa[i] != 0) mpz_mul_2exp(out[i].get_mpz_t(), out[i].get_mpz_t(), exponent[i] - smallest);
  }
}

}  // namespace

int gmp_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                 const Eigen::Vector3d& s) {
  std::array<mpz_class, 12> z;
  to_integers<12>({p[0], p[1], p[2], q[0], q[1], q[2], r[0], r[1], r[2], s[0], s[1], s[2]}, z);
  mpz_class e1[3], e2[3], d[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = z[3 + k] - z[k];
    e2[k] = z[6 + k] - z[k];
    d[k] = z[9 + k] - z[k];
  }
  const mpz_class det = d[0] * (e1[1] * e2[2] - e1[2] * e2[1]) + d[1] * (e1[2] * e2[0] - e1[0] * e2[2]) +
                        d[2] * (e1[0] * e2[1] - e1[1] * e2[0]);
  return sgn(det);
}

int gmp_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int drop_axis) {
  const int i = (drop_axis + 1) % 3, j = (drop_axis + 2) % 3;
  std::array<mpz_class, 6> z;
  to_integers<6>({p[i], p[j], q[i], q[j], r[i], r[j]}, z);
  const mpz_class ei = z[2] - z[0], ej = z[3] - z[1], fi = z[4] - z[0], fj = z[5] - z[1];
  return sgn(mpz_class(ei * fj - ej * fi));
}

}  // namespace clothcd::geometry
