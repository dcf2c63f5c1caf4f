#pragma once
// Private: exact real numbers as floating-point expansions (Shewchuk 1997, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates"): a sum of doubles, non-overlapping, increasing in magnitude,
// without zeros. Sums, differences and products are exact as long as no intermediate overflows and every exact
// product stays a multiple of 2^-1074 (callers keep their inputs on a coarse enough dyadic grid, see
// expansion_collision.cpp), so the sign of the largest component is the exact sign. The components live inline (no
// allocation); a result longer than kCapacity throws ExpansionCapacityExceeded.
#include <cstddef>
#include <stdexcept>

namespace clothcd::geometry::detail {

/// Thrown when an expansion would need more than Expansion::kCapacity components.
struct ExpansionCapacityExceeded : std::length_error {
  ExpansionCapacityExceeded() : std::length_error("floating-point expansion too long") {}
};

/// An exact dyadic rational number as a floating-point expansion.
class Expansion {
 public:
  /// Most components an expansion holds.
  static constexpr std::size_t kCapacity = 64;

  Expansion() = default;
  Expansion(const Expansion& other) { *this = other; }
  Expansion& operator=(const Expansion& other) {
    size_ = other.size_;
    for (std::size_t i = 0; i < size_; ++i) terms_[i] = other.terms_[i];
    return *this;
  }
  /// The double x, exactly.
  explicit Expansion(double x);
  /// Exact a - b.
  [[nodiscard]] static Expansion difference(double a, double b);

  /// Exact *this + b in place (b may be *this).
  Expansion& operator+=(const Expansion& b);
  /// Exact *this - b in place (b may be *this).
  Expansion& operator-=(const Expansion& b);
  friend Expansion operator+(const Expansion& a, const Expansion& b);
  friend Expansion operator-(const Expansion& a, const Expansion& b);
  friend Expansion operator*(const Expansion& a, const Expansion& b);
  /// Exact product with one double.
  [[nodiscard]] Expansion scaled(double b) const;
  [[nodiscard]] Expansion operator-() const;

  /// Exact sign: -1, 0 or 1.
  [[nodiscard]] int sign() const { return size_ == 0 ? 0 : (terms_[size_ - 1] > 0.0 ? 1 : -1); }
  [[nodiscard]] bool is_zero() const { return size_ == 0; }
  /// True when the expansion is x itself in one component (false can still mean an equal value in several).
  [[nodiscard]] bool is_double(double x) const { return x == 0.0 ? size_ == 0 : size_ == 1 && terms_[0] == x; }
  /// The value rounded to about double precision (the components summed from the smallest).
  [[nodiscard]] double estimate() const;
  /// e with 2^e <= |largest component| < 2^(e + 1); the value must be non-zero.
  [[nodiscard]] int top_exponent() const;
  /// e with 2^e the lowest set bit of the smallest component; the value must be non-zero.
  [[nodiscard]] int bottom_exponent() const;
  /// The value times 2^k (exact while the components stay normal and finite).
  [[nodiscard]] Expansion times_power_of_two(int k) const;
  /// The same value in usually fewer components (Shewchuk's compression; the result is non-adjacent).
  [[nodiscard]] Expansion compressed() const;

 private:
  void push(double x) {
    if (size_ == kCapacity) throw ExpansionCapacityExceeded();
    terms_[size_++] = x;
  }
  friend void sum_into(const Expansion& e, const Expansion& f, double f_sign, Expansion& h);

  std::size_t size_ = 0;
  double terms_[kCapacity];  // terms_[0..size_): non-overlapping, increasing magnitude, no zeros
};

}  // namespace clothcd::geometry::detail
