#pragma once
// GMP rationals for the exact paths. Included by kernel/contact .cpp files only, never by a
// public header, so users of the library do not compile against gmpxx.
//
// NumberOps<FT> gives the few operations the FT-generic constructions need beyond + - * /:
// sqrt (the potential divides by edge lengths, the only irrational quantity; for rationals it
// is evaluated at 256 bits, i.e. a relative error below 1e-76) and conversion to double.

#include <gmpxx.h>

#include <cmath>
#include <type_traits>

#include "rockcontact/kernel/detail/number_ops.hpp"
#include "rockcontact/kernel/number_policy.hpp"

namespace rockcontact::kernel::detail {

template <>
struct NumberOps<mpq_class> {
  static mpq_class from(double x) { return mpq_class(x); }
  static double to_double(const mpq_class& x) { return x.get_d(); }
  static mpq_class abs(const mpq_class& x) { return ::abs(x); }
  static mpq_class sqrt(const mpq_class& x) {
    if (sgn(x) <= 0) return mpq_class(0);
    mpf_class f(x, 256);
    mpf_class r(0, 256);
    mpf_sqrt(r.get_mpf_t(), f.get_mpf_t());
    return mpq_class(r);
  }
};

// Returns mpq_class, not a GMP expression template (which would dangle its temporaries).
inline auto exact_diff = [](double a, double b) -> mpq_class { return mpq_class(a) - mpq_class(b); };

}  // namespace rockcontact::kernel::detail

namespace rockcontact::kernel::detail {

// The number type a policy constructs in.
template <class Policy>
using ConstructionType =
    std::conditional_t<Policy::kind == PolicyKind::exact, mpq_class, double>;

}  // namespace rockcontact::kernel::detail
