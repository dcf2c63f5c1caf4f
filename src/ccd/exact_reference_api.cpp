// Public entry of the exact rational CCD reference on rational text coordinates (see exact_reference.cpp).
#include <stdexcept>

#include "ccd/exact_reference.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd {

bool exact_collision_reference(PairKind kind, const std::array<std::array<std::array<std::string, 2>, 3>, 8>& points) {
  exact::RationalPoints rational;
  for (int i = 0; i < 8; ++i) {
    for (int d = 0; d < 3; ++d) {
      mpz_class numerator;
      mpz_class denominator;
      const std::string& n = points[i][d][0];
      const std::string& m = points[i][d][1];
      if (numerator.set_str(n[0] == '+' ? n.substr(1) : n, 10) != 0 ||
          denominator.set_str(m[0] == '+' ? m.substr(1) : m, 10) != 0)
        throw std::invalid_argument("exact_collision_reference: not an integer: '" + n + "/" + m + "'");
      if (denominator == 0) throw std::invalid_argument("exact_collision_reference: zero denominator");
      rational[i][d] = mpq_class(numerator, denominator);
      rational[i][d].canonicalize();
    }
  }
  return exact::exact_collision(kind, rational).hit;
}

}  // namespace clothcd::ccd
