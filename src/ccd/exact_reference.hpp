#pragma once
// Private: the exact rational CCD reference on GMP coordinates, with the earliest time of impact.
#include <gmpxx.h>

#include <array>

#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd::ccd::exact {

/// Eight points (four at t = 0, then four at t = 1, benchmark order), exact rational coordinates.
using RationalPoints = std::array<std::array<mpq_class, 3>, 8>;

/// Exact answer: hit, and a lower bound of the earliest contact time (rounded down to double) when hit.
struct ExactAnswer {
  bool hit = false;
  double toi = 1.0;
};

/// The exact earliest contact time of a hit enclosed in [lo, hi] (doubles rounded outwards), hi - lo <= 2^-40 + 2^-52.
struct ContactTimeBounds {
  bool hit = false;  ///< False when the primitives never touch in [0, 1] (lo = hi = 1 then).
  double lo = 1.0;   ///< Lower bound of the earliest contact time.
  double hi = 1.0;   ///< Upper bound of the earliest contact time.
};

/// Decides exactly whether the primitives touch or cross for some t in [0, 1] (thickness 0).
[[nodiscard]] ExactAnswer exact_collision(PairKind kind, const RationalPoints& points);

/// Like exact_collision, with the earliest contact time narrowed by exact bisection (the slow reference for tests).
[[nodiscard]] ContactTimeBounds exact_contact_time(PairKind kind, const RationalPoints& points);

}  // namespace clothcd::ccd::exact
