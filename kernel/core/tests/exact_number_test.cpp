#define BOOST_TEST_MODULE kernel_core_exact_number
#include <boost/test/unit_test.hpp>

// The Exact policy's rounding and square root (kernel/core/detail/exact_number.hpp) on cases
// whose answers follow from the definition of round-to-nearest-even: exact doubles, ties on
// both sides of an even and an odd significand, values between the largest double and the
// overflow threshold, and square roots against MPFR at 1024 bits.

#include <cmath>
#include <limits>
#include <vector>

#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rkd = rockcontact::kernel::detail;
using Q = rkd::ExactRational;
using Ops = rkd::NumberOps<Q>;

namespace {

Q power_of_two(int e) { return Q(std::ldexp(1.0, e)); }

}  // namespace

BOOST_AUTO_TEST_CASE(rounds_to_nearest_ties_to_even) {
  BOOST_TEST(Ops::to_double(Q(0.1)) == 0.1);
  BOOST_TEST(Ops::to_double(Q(1) / 3) == 1.0 / 3.0);  // IEEE division rounds to nearest
  // 1 + 2^-53 lies halfway between 1 (even) and 1 + 2^-52 (odd).
  BOOST_TEST(Ops::to_double(Q(1) + power_of_two(-53)) == 1.0);
  // 1 + 3 2^-53 lies halfway between 1 + 2^-52 (odd) and 1 + 2^-51 (even).
  BOOST_TEST(Ops::to_double(Q(1) + 3 * power_of_two(-53)) == 1.0 + 0x1p-51);
  // Just off the tie, either way.
  BOOST_TEST(Ops::to_double(Q(1) + power_of_two(-53) + power_of_two(-80)) == 1.0 + 0x1p-52);
  BOOST_TEST(Ops::to_double(-(Q(1) + power_of_two(-53))) == -1.0);
}

BOOST_AUTO_TEST_CASE(rounds_beyond_the_largest_double) {
  const double max = std::numeric_limits<double>::max();  // odd significand, ulp 2^971
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(Ops::to_double(Q(max)) == max);
  BOOST_TEST(Ops::to_double(Q(max) + power_of_two(969)) == max);   // below the midpoint
  BOOST_TEST(Ops::to_double(Q(max) + power_of_two(970)) == inf);   // the tie: max is odd
  BOOST_TEST(Ops::to_double(Q(max) * 4) == inf);
  BOOST_TEST(Ops::to_double(-(Q(max) + power_of_two(969))) == -max);
  BOOST_TEST(Ops::to_double(-(Q(max) + power_of_two(970))) == -inf);
}

// The square root at exact_sqrt_precision (256) bits: two roundings to nearest, so its
// relative error is below 2^-255; checked against MPFR at 1024 bits.
BOOST_AUTO_TEST_CASE(square_root_within_its_stated_precision) {
  BOOST_TEST(rkd::exact_sqrt_precision == 256);
  const std::vector<Q> inputs{Q(2), Q(Q(1) / 3), Q(1e-300), Q(7e300), Q(0.5)};
  for (const Q& x : inputs) {
    const Q root = Ops::sqrt(x);
    mpfr_t reference, error;
    mpfr_inits2(1024, reference, error, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_q(reference, x.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(reference, reference, MPFR_RNDN);
    mpfr_set_q(error, root.get_mpq_t(), MPFR_RNDN);
    mpfr_sub(error, error, reference, MPFR_RNDN);
    mpfr_div(error, error, reference, MPFR_RNDN);
    mpfr_abs(error, error, MPFR_RNDN);
    BOOST_TEST_INFO("sqrt of " << x.get_d());
    BOOST_TEST(mpfr_cmp_d(error, 0x1p-255) < 0);
    mpfr_clears(reference, error, static_cast<mpfr_ptr>(nullptr));
  }
  BOOST_TEST(Ops::sqrt(Q(0)) == Q(0));
  BOOST_TEST(Ops::sqrt(Q(4)) == Q(2));
}
