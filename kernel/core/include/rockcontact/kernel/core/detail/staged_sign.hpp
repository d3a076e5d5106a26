#pragma once
// The interval and exact stages of a staged predicate, shared by the 2D and 3D kernels.
// Included by kernel .cpp files only: it includes CGAL, which public headers never do.
//
// A predicate is a polynomial formula of its input doubles written once, generic over its
// number type T (e.g. kernel/2d/detail/predicate_formulas.hpp). Here a *formula* is a callable
// f with f(As<T>{}) evaluating it in T; a predicate on a derived point (an entrance-block
// vertex b_j - a_i, a crossing of two edges, in 3D a point on three planes) is just another
// formula of the input doubles, so an indirect predicate needs a formula, not a new engine.
// The stages, as in CGAL's Filtered_predicate and geogram's PCK:
//   1. double filter: inline in the predicate's header, with a proven bound (static or
//      semi-static); it answers almost always and needs no rounding-mode switch;
//   2. interval: f in CGAL::Interval_nt_advanced with the FPU rounding upward, switched for this
//      evaluation alone and restored after it (CGAL::Protect_FPU_rounding). All other double
//      code, the filters included, runs in round to nearest: it is the mode the compilers
//      assume (neither honours FENV_ACCESS), and a filter run under upward rounding once gave a
//      wrong sign, its overflow saturating at DBL_MAX where a rewritten |x| |y| = |x y| read
//      it. A switch costs a few cycles beside the interval evaluation. The sign is certain when the
//      interval excludes zero, or is the point [0, 0], which happens when every operation was
//      exact: an exact touch between dyadic coordinates is settled here, without GMP;
//   3. exact: f in CGAL::Mpzf, an exact ring of floating-point integers that holds a product
//      of a few doubles in its inline limbs (no allocation below 8 limbs); + - * are all the
//      formulas use, so its sign is the exact sign.
// Each stage counts its entries in the thread-local counters of predicate_stats.hpp.

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <span>

#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel::detail {

template <class T>
struct As {
  using type = T;
};

// T(a) - T(b): the difference of two input doubles in T (rounded in double, an enclosure in
// intervals, exact in Mpzf and rationals).
template <class T>
T difference(double a, double b) {
  return T(a) - T(b);
}

inline Sign to_sign(CGAL::Sign s) { return static_cast<Sign>(static_cast<int>(s)); }

template <class Formula>
Sign exact_sign(const Formula& f) {
  return to_sign(CGAL::sign(f(As<CGAL::Mpzf>{})));
}

// Stages 2 and 3, for a call whose double filter was uncertain.
template <class Formula>
Sign interval_then_exact_sign(PredicateKind kind, const Formula& f) {
  count_interval_fallback(kind);
  {
    const CGAL::Protect_FPU_rounding<true> upward(CGAL_FE_UPWARD);
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(f(As<CGAL::Interval_nt_advanced>{}));
    if (CGAL::is_certain(s)) return to_sign(CGAL::get_certain(s));
  }
  count_fallback(kind);
  return exact_sign(f);
}

// The Checked policy's report: throws PolicyDisagreement naming the predicate, both signs and
// the input coordinates as hexadecimal floats (core/src/staged_sign.cpp).
[[noreturn]] void throw_disagreement(PredicateKind kind, std::span<const double> input, Sign staged,
                                     Sign exact);

}  // namespace rockcontact::kernel::detail
