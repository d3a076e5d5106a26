#pragma once
// RunningError: a number with a running bound on its error. In double, the number type of the
// plane formulas' double filter (plane.cpp) and of the certified double vertices
// (halfspace_polyhedron.cpp); in DoubleDouble (core/detail/double_double.hpp), the lazy stage
// of the Exact constructions (the volume). The formulas are the same as for the interval and
// exact stages (detail/plane_formulas.hpp), evaluated once more with this type.

#include <cmath>

#include "rockcontact/kernel/core/detail/double_double.hpp"

namespace rockcontact::kernel::detail {

// The relative rounding bound of one operation on V, and |v| from above.
template <class V>
struct RunningErrorTraits;

// Any IEEE rounding mode: an operation errs by less than an ulp of its result, at most
// 2^-52 |result| (to nearest by half that).
template <>
struct RunningErrorTraits<double> {
  static constexpr double unit = 0x1p-52;
  static double magnitude(double v) { return std::fabs(v); }
  static bool finite(double v) { return std::isfinite(v); }
};

// Round to nearest only (double_double.hpp): 2^-100 is 8 times the proven bound of the
// multiplication, 16 times that of the addition.
template <>
struct RunningErrorTraits<DoubleDouble> {
  static constexpr double unit = 0x1p-100;
  static double magnitude(const DoubleDouble& v) { return v.magnitude(); }
  static bool finite(const DoubleDouble& v) { return v.finite(); }
};

// A number with a running bound on its error (Higham, Accuracy and Stability of Numerical
// Algorithms, sec. 3.3): every operation adds its own rounding, at most unit |result| plus
// 2^-1069 for a result in the subnormal range (double: one rounding of at most 2^-1075;
// DoubleDouble: its low word's roundings there, a handful of at most 2^-1075 each), to the
// errors propagated from its operands,
//   (a +- b): ea + eb,     (a * b): |a| eb + |b| ea + ea eb.
// The bound is itself computed in double, from non-negative terms: at most 6 roundings per
// operation over a formula of depth <= 14 (the three-plane side), so it is at most 84 eps below
// the exact running bound, which the factor 1 + 2^-40 applied where the bound is used covers. An
// input double carries no error; a non-finite value or bound means nothing is certified.
template <class V>
struct RunningErrorOf {
  using Traits = RunningErrorTraits<V>;
  V value{};
  double error = 0.0;
  RunningErrorOf() = default;
  explicit RunningErrorOf(double x) : value(x) {}
  RunningErrorOf(V v, double e) : value(v), error(e) {}
  static double rounding(const V& v) { return Traits::unit * Traits::magnitude(v) + 0x1p-1069; }
  double magnitude() const { return Traits::magnitude(value); }
  // The value and its bound are finite: only then does the bound mean anything.
  bool finite() const { return Traits::finite(value) && std::isfinite(error); }
  friend RunningErrorOf operator+(const RunningErrorOf& a, const RunningErrorOf& b) {
    const V v = a.value + b.value;
    return {v, a.error + b.error + rounding(v)};
  }
  friend RunningErrorOf operator-(const RunningErrorOf& a, const RunningErrorOf& b) {
    const V v = a.value - b.value;
    return {v, a.error + b.error + rounding(v)};
  }
  friend RunningErrorOf operator*(const RunningErrorOf& a, const RunningErrorOf& b) {
    const V v = a.value * b.value;
    return {v, a.magnitude() * b.error + b.magnitude() * a.error + a.error * b.error + rounding(v)};
  }
};
using RunningError = RunningErrorOf<double>;
inline constexpr double bound_rounding_margin = 1.0 + 0x1p-40;

}  // namespace rockcontact::kernel::detail
