// Stage 2 of the filtered predicates: the same formulas evaluated in GMP rationals.
// Every double is an exact rational, and the formulas use + - * only, so the sign is exact.

#include <gmpxx.h>

#include "rockcontact/kernel/core/detail/exact_number.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"

namespace rockcontact::kernel::detail {

Sign cross_sign_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  return sign_of(cross_formula<mpq_class>(p0, p1, q0, q1, exact_diff));
}

Sign crossing_side_value_sign_exact(const Line& a, const Line& b, const Line& c) {
  return sign_of(crossing_side_formula<mpq_class>(a, b, c, exact_diff));
}

}  // namespace rockcontact::kernel::detail
