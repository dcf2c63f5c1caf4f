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

/// Decides exactly whether the primitives touch or cross for some t in [0, 1] (thickness 0).
[[nodiscard]] ExactAnswer exact_collision(PairKind kind, const RationalPoints& points);

}  // namespace clothcd::ccd::exact
