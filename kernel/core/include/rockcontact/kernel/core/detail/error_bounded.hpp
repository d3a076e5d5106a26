#pragma once
// ErrorBounded: a double carrying a certified bound on its absolute error, the floating-point
// filter for predicates whose formula is too long for a hand-derived static bound.
//
// Invariant: for the exact real value X that an ErrorBounded e stands for, |X - e.value| <=
// e.error. With u = 2^-53 (unit roundoff, round to nearest) and eta = 2^-1074 (the smallest
// subnormal), each operation maintains it:
//   difference of two doubles a - b   value = fl(a - b)  error = u|value|
//       (|fl(s) - s| <= u|fl(s)| for round to nearest; subnormal sums are exact)
//   x +- y                            error = ex + ey + u|value|
//   x * y                             error = ex|y| + |x|ey + ex ey + u|value| + eta
//       (|XY - xy| <= |x||Y-y| + |y||X-x| + |X-x||Y-y|; eta covers a subnormal product)
// The error terms are themselves rounded; each is a sum of at most five non-negative rounded
// terms, so a computed bound under-estimates the true one by at most a factor (1 - u)^(5 d) for
// an expression of depth d. certain_sign() therefore inflates the bound by 2^-40, which covers
// any depth below 2^10 with a wide margin. Overflow shows as a non-finite value or bound, and
// makes certain_sign() answer "uncertain".

#include <cmath>
#include <optional>

#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel::detail {

inline constexpr double unit_roundoff = 0x1p-53;
inline constexpr double smallest_subnormal = 0x1p-1074;

struct ErrorBounded {
  double value = 0.0;
  double error = 0.0;

  static ErrorBounded difference(double a, double b) {
    const double v = a - b;
    return {v, unit_roundoff * std::fabs(v)};
  }

  friend ErrorBounded operator+(ErrorBounded x, ErrorBounded y) {
    const double v = x.value + y.value;
    return {v, x.error + y.error + unit_roundoff * std::fabs(v)};
  }
  friend ErrorBounded operator-(ErrorBounded x, ErrorBounded y) {
    const double v = x.value - y.value;
    return {v, x.error + y.error + unit_roundoff * std::fabs(v)};
  }
  friend ErrorBounded operator*(ErrorBounded x, ErrorBounded y) {
    const double v = x.value * y.value;
    return {v, x.error * std::fabs(y.value) + std::fabs(x.value) * y.error + x.error * y.error +
                   unit_roundoff * std::fabs(v) + smallest_subnormal};
  }
};

// The sign of the exact value when the bound certifies it, else nullopt.
inline std::optional<Sign> certain_sign(const ErrorBounded& x) {
  const double bound = x.error * (1.0 + 0x1p-40);
  if (!std::isfinite(x.value) || !std::isfinite(bound)) return std::nullopt;
  if (x.value > bound) return Sign::positive;
  if (-x.value > bound) return Sign::negative;
  if (x.error == 0.0) return sign_of(x.value);  // every step was exact
  return std::nullopt;
}

}  // namespace rockcontact::kernel::detail
