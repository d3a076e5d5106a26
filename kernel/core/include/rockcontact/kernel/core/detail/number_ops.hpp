#pragma once
// NumberOps<FT>: the operations FT-generic constructions need beyond + - * / and comparison.
// The double specialisation lives here; the GMP one in exact_number.hpp (kernel .cpp files only).
// ConstructionType<Policy> (exact_number.hpp) names the number type a policy constructs in.

#include <cmath>

#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel::detail {

template <class FT>
struct NumberOps;

template <>
struct NumberOps<double> {
  static double from(double x) { return x; }
  static double to_double(double x) { return x; }
  static double abs(double x) { return std::fabs(x); }
  static double sqrt(double x) { return x > 0.0 ? std::sqrt(x) : 0.0; }
};

}  // namespace rockcontact::kernel::detail
