#define BOOST_TEST_MODULE kernel_core_double_double
#include <boost/test/unit_test.hpp>

// DoubleDouble (kernel/core/detail/double_double.hpp) re-derived against GMP rationals: the
// error-free transformations are exact, and addition and multiplication stay within the bounds
// the header states (4 u^2 and 8 u^2 of the exact result, u = 2^-53), on random operands of
// mixed signs and exponents, on sums that cancel to a few ulps, and on products of operands with
// full 106-bit significands. The lazy Exact volume takes 2^-100 per operation from these.

#include <gmpxx.h>

#include <cmath>
#include <random>

#include "rockcontact/kernel/core/detail/double_double.hpp"
#include "rockcontact/testing/seed.hpp"

using rockcontact::kernel::detail::DoubleDouble;

namespace {

mpq_class exact(const DoubleDouble& x) { return mpq_class(x.hi) + mpq_class(x.lo); }

// |x - y| / |y| as a double, y != 0.
double relative_error(const DoubleDouble& x, const mpq_class& y) {
  const mpq_class d = abs(exact(x) - y) / abs(y);
  return d.get_d();
}

// A normalized DoubleDouble with a random significand of about 106 bits and exponent in
// [-e, e], either sign.
struct Operands {
  std::mt19937_64 rng;
  explicit Operands(std::uint64_t seed) : rng(seed) {}
  DoubleDouble next(int e) {
    std::uniform_real_distribution<double> unit(0.5, 1.0);
    std::uniform_int_distribution<int> exponent(-e, e);
    const int k = exponent(rng);
    const double hi = std::ldexp(unit(rng), k) * (rng() % 2 ? 1.0 : -1.0);
    const double lo = std::ldexp(unit(rng), k - 54) * (rng() % 2 ? 1.0 : -1.0);
    return DoubleDouble::fast_two_sum(hi, lo);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(error_free_transformations_are_exact) {
  Operands ops(rockcontact::testing::seed_for("error_free_transformations_are_exact", 20261127));
  for (int i = 0; i < 20000; ++i) {
    const double a = ops.next(60).hi, b = ops.next(60).hi;
    const mpq_class sum = mpq_class(a) + mpq_class(b), product = mpq_class(a) * mpq_class(b);
    BOOST_TEST(exact(DoubleDouble::two_sum(a, b)) == sum);
    BOOST_TEST(exact(DoubleDouble::two_product(a, b)) == product);
    const double big = std::fabs(a) >= std::fabs(b) ? a : b, small = big == a ? b : a;
    BOOST_TEST(exact(DoubleDouble::fast_two_sum(big, small)) == sum);
  }
}

BOOST_AUTO_TEST_CASE(sums_and_products_within_the_stated_bounds) {
  Operands ops(rockcontact::testing::seed_for("sums_and_products_within_the_stated_bounds", 20261127));
  const double sum_bound = 4 * 0x1p-106, product_bound = 8 * 0x1p-106;
  double worst_sum = 0.0, worst_product = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const DoubleDouble a = ops.next(30), b = ops.next(i % 4 == 0 ? 0 : 30);
    // Every fourth pair: b close to -a, so the sum cancels all but the low words.
    const DoubleDouble c = i % 4 == 0 ? DoubleDouble::fast_two_sum(-a.hi, b.lo) : b;
    const mpq_class sum = exact(a) + exact(c);
    if (sum != 0) worst_sum = std::max(worst_sum, relative_error(a + c, sum));
    worst_product = std::max(worst_product, relative_error(a * b, exact(a) * exact(b)));
  }
  BOOST_TEST_MESSAGE("worst relative error: sum " << worst_sum / 0x1p-106 << " u^2, product "
                                                  << worst_product / 0x1p-106 << " u^2");
  BOOST_TEST(worst_sum <= sum_bound);
  BOOST_TEST(worst_product <= product_bound);
}

// Normalized results: |lo| <= ulp(hi) / 2, which the users' lower bound |hi| (1 - 2^-52) on
// |hi + lo| relies on.
BOOST_AUTO_TEST_CASE(results_are_normalized) {
  Operands ops(rockcontact::testing::seed_for("results_are_normalized", 20261127));
  for (int i = 0; i < 20000; ++i) {
    const DoubleDouble a = ops.next(30), b = ops.next(30);
    for (const DoubleDouble& r : {a + b, a - b, a * b}) {
      BOOST_TEST(r.hi + r.lo == r.hi);
      BOOST_TEST(std::fabs(r.lo) <= std::ldexp(1.0, std::ilogb(r.hi) - 53));
    }
  }
}
