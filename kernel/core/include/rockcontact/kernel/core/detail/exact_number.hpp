#pragma once
// The Exact policy's construction number type: CGAL::Exact_rational. Included by kernel and
// contact .cpp files only, never by a public header, so users do not compile against CGAL.
//
// NumberOps<Exact_rational> gives the few operations the FT-generic constructions need beyond
// + - * /:
//   to_double  round to nearest, ties to even, from CGAL's tight enclosure (to_interval) and
//              one exact comparison with the midpoint of the two candidate doubles (overflow
//              included: infinity stands for 2^1024);
//   sqrt       the only irrational operation (the potential divides by edge lengths): MPFR
//              (CGAL::Gmpfr) at exact_sqrt_precision bits, round to nearest twice (the
//              rational to MPFR, then the root), so the relative error is below 2^-255; the
//              result is a dyadic rational and the computation stays exact from there on.

#include <CGAL/Exact_rational.h>
#include <CGAL/Gmpfr.h>
#include <CGAL/Gmpq.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "rockcontact/kernel/core/detail/number_ops.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel::detail {

using ExactRational = CGAL::Exact_rational;

// MPFR's square root reads the rational through GMP's mpq interface.
static_assert(std::is_same_v<ExactRational, mpq_class>,
              "CGAL must be configured with gmpxx (CGAL_USE_GMPXX), as the kernel's CMake does");

inline constexpr long exact_sqrt_precision = 256;  // bits

template <>
struct NumberOps<ExactRational> {
  static ExactRational from(double x) { return ExactRational(x); }
  static double to_double(const ExactRational& x) {
    const auto [lo, hi] = CGAL::to_interval(x);
    if (lo == hi) return lo;
    // Beyond the largest double the enclosure's outer bound is infinite; rounding treats it
    // as the next power of two, 2^1024, so values below the midpoint still round to the
    // largest double (whose odd significand loses a tie to infinity).
    const auto value = [](double d) {
      return std::isfinite(d) ? ExactRational(d) : ExactRational(std::ldexp(d > 0 ? 1.0 : -1.0, 1023)) * 2;
    };
    const ExactRational midpoint = (value(lo) + value(hi)) / 2;
    const CGAL::Comparison_result c = CGAL::compare(x, midpoint);
    if (c == CGAL::SMALLER) return lo;
    if (c == CGAL::LARGER) return hi;
    return (std::bit_cast<std::uint64_t>(lo) & 1u) == 0 ? lo : hi;  // a tie: the even one
  }
  static ExactRational abs(const ExactRational& x) { return CGAL::abs(x); }
  static ExactRational sqrt(const ExactRational& x) {
    if (CGAL::sign(x) <= 0) return ExactRational(0);
    CGAL::Gmpfr value(0, exact_sqrt_precision);
    mpfr_set_q(value.fr(), x.get_mpq_t(), MPFR_RNDN);
    const CGAL::Gmpq root(value.sqrt(exact_sqrt_precision, std::round_to_nearest));
    return ExactRational(root.mpq());
  }
};

// The number type a policy constructs in.
template <class Policy>
using ConstructionType = std::conditional_t<Policy::kind == PolicyKind::exact, ExactRational, double>;

}  // namespace rockcontact::kernel::detail
