#include "bench/ccd/ccd_query.hpp"

#include <mpfr.h>

namespace grip::bench {

namespace {

// mpq_get_d truncates toward zero; MPFR rounds to nearest like every other input path.
double nearest_double(const mpq_class& value) {
  mpfr_t rounded;
  mpfr_init2(rounded, 53);
  mpfr_set_q(rounded, value.get_mpq_t(), MPFR_RNDN);
  const double result = mpfr_get_d(rounded, MPFR_RNDN);
  mpfr_clear(rounded);
  return result;
}

}  // namespace

CcdQuery to_double_query(const RationalCcdQuery& query) {
  CcdQuery out;
  for (std::size_t row = 0; row < kCcdQueryRows; ++row) {
    for (int axis = 0; axis < 3; ++axis) {
      out.vertices[row][axis] = nearest_double(query.vertices[row][axis]);
    }
  }
  out.collides = query.collides;
  return out;
}

}  // namespace grip::bench
