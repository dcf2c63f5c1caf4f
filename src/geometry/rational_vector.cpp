// Exact rational vector arithmetic for the pair distances.
#include "geometry/rational_vector.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

namespace clothcd::geometry::rational {

namespace {

// For x != 0: the difference of the bit lengths of numerator and denominator, so that log2 |x| is within 1 of it.
long binary_exponent(const mpq_class& x) {
  return static_cast<long>(mpz_sizeinbase(x.get_num_mpz_t(), 2)) -
         static_cast<long>(mpz_sizeinbase(x.get_den_mpz_t(), 2));
}

// x 2^e, exactly.
mpq_class times_power_of_two(const mpq_class& x, long e) {
  mpq_class y;
  if (e >= 0) {
    mpq_mul_2exp(y.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  } else {
    mpq_div_2exp(y.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  }
  return y;
}

}  // namespace

Vector from_double(const Eigen::Vector3d& x) {
  return {mpq_class(x.x()), mpq_class(x.y()), mpq_class(x.z())};
}

Vector operator-(const Vector& a, const Vector& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Vector operator+(const Vector& a, const Vector& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

Vector operator*(const mpq_class& s, const Vector& a) {
  return {s * a[0], s * a[1], s * a[2]};
}

mpq_class dot(const Vector& a, const Vector& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vector cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool is_zero(const Vector& a) {
  return sgn(a[0]) == 0 && sgn(a[1]) == 0 && sgn(a[2]) == 0;
}

double square_root(const mpq_class& x) {
  if (sgn(x) <= 0) return 0.0;
  const long half = binary_exponent(x) / 2;
  return std::ldexp(std::sqrt(times_power_of_two(x, -2 * half).get_d()), static_cast<int>(half));
}

Eigen::Vector3d unit_direction(const Vector& a) {
  if (is_zero(a)) return Eigen::Vector3d::Zero();
  // Scaled by a power of two first, so that components outside the double range keep their ratios.
  long largest = LONG_MIN;
  for (const mpq_class& c : a)
    if (sgn(c) != 0) largest = std::max(largest, binary_exponent(c));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = times_power_of_two(a[i], -largest).get_d();
  return v.normalized();
}

}  // namespace clothcd::geometry::rational
