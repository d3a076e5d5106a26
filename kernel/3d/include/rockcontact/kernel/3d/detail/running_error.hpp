#pragma once
// RunningError: a double with a running bound on its error, the number type of the plane
// formulas' double filter (plane.cpp) and of the certified double vertices
// (halfspace_polyhedron.cpp). The formulas are the same as for the interval and exact stages
// (detail/plane_formulas.hpp), evaluated once more with this type.

#include <cmath>

namespace rockcontact::kernel::detail {

// A double with a running bound on its error (Higham, Accuracy and Stability of Numerical
// Algorithms, sec. 3.3): every operation adds its own rounding, at most eps |result| with
// eps = 2^-52 (any rounding mode) plus 2^-1069 for a result in the subnormal range, to the
// errors propagated from its operands,
//   (a +- b): ea + eb,     (a * b): |a| eb + |b| ea + ea eb.
// (Under directed rounding an operation errs by less than an ulp of its computed result, at most
// 2^-52 |result|; to nearest by half that.) The bound is itself computed in double, from
// non-negative terms: at most 6 roundings per operation over a formula of depth <= 14 (the
// three-plane side), so it is at most 84 eps below the exact running bound, which the factor
// 1 + 2^-40 applied where the bound is used covers. An input double carries no error; a
// non-finite value or bound means nothing is certified.
struct RunningError {
  double value = 0.0;
  double error = 0.0;
  RunningError() = default;
  explicit RunningError(double x) : value(x) {}
  RunningError(double v, double e) : value(v), error(e) {}
  static double rounding(double v) { return 0x1p-52 * std::fabs(v) + 0x1p-1069; }
  friend RunningError operator+(RunningError a, RunningError b) {
    const double v = a.value + b.value;
    return {v, a.error + b.error + rounding(v)};
  }
  friend RunningError operator-(RunningError a, RunningError b) {
    const double v = a.value - b.value;
    return {v, a.error + b.error + rounding(v)};
  }
  friend RunningError operator*(RunningError a, RunningError b) {
    const double v = a.value * b.value;
    return {v, std::fabs(a.value) * b.error + std::fabs(b.value) * a.error + a.error * b.error + rounding(v)};
  }
};
inline constexpr double bound_rounding_margin = 1.0 + 0x1p-40;

}  // namespace rockcontact::kernel::detail
