#pragma once
// GMP rationals for the exact paths. Included by kernel/contact .cpp files only, never by a
// public header, so users of the library do not compile against gmpxx.
//
// NumberOps<FT> gives the few operations the FT-generic constructions need beyond + - * /:
// sqrt (the potential divides by edge lengths, the only irrational quantity; for rationals it
// is evaluated at 256 bits, i.e. a relative error below 1e-76) and conversion to double.

#include <gmpxx.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "rockcontact/kernel/core/detail/number_ops.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel::detail {

template <>
struct NumberOps<mpq_class> {
  static mpq_class from(double x) { return mpq_class(x); }
  // Round to nearest, ties to even. mpq_get_d truncates toward zero, so the nearest double
  // is either its answer or the next double away from zero; the exact errors decide.
  static double to_double(const mpq_class& x) {
    const double truncated = x.get_d();
    if (sgn(x) == 0 || !std::isfinite(truncated)) return truncated;
    const double away = std::nextafter(truncated, sgn(x) > 0 ? HUGE_VAL : -HUGE_VAL);
    if (!std::isfinite(away)) return truncated;
    const mpq_class error_truncated = ::abs(x - mpq_class(truncated));
    const mpq_class error_away = ::abs(x - mpq_class(away));
    const int c = cmp(error_away, error_truncated);
    if (c < 0) return away;
    if (c == 0 && (std::bit_cast<std::uint64_t>(truncated) & 1u) != 0) return away;
    return truncated;
  }
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
