#pragma once
// Geometric predicates under a number policy. Each returns a Sign.
//
//   cross_sign(p0, p1, q0, q1)      sign of (p1 - p0) x (q1 - q0)
//   orientation(p, q, r)            sign of (q - p) x (r - p): positive = left turn (CCW)
//   crossing_side(a, b, c)          side of the crossing point of lines a and b w.r.t. line c
//
// All of them read input coordinates only. cross_sign covers the derived points the library
// decides on: an entrance-block vertex b_j - a_i tested against an entrance-block edge reduces
// to a cross product of two input differences (see entrance_block.hpp), and a clipped point is
// a line-line crossing, tested with crossing_side on the lines' defining input points.
//
// Staged evaluation (kernel/core/detail/staged_sign.hpp), the same under Filtered, Exact and
// Checked since a sign has only one exact value:
//   1. double filter, inline here: cross has a static bound, crossing_side a semi-static one
//      and a check that a or b is c's own line (which settles crossings on collinear edges);
//      they run in round to nearest, the library's mode outside an interval stage, and take
//      eps = 2^-52 per operation, a whole ulp: twice round to nearest's error, and enough for
//      any rounding mode as long as nothing overflows (a directed mode saturates an overflow
//      at DBL_MAX instead of infinity, which the filters' finiteness checks would not see);
//   2. interval: the formula in CGAL::Interval_nt_advanced (predicates_staged.cpp); it settles
//      exact zeros whose operations are all exact (touching dyadic coordinates);
//   3. exact: the formula in CGAL::Mpzf;
//   no symbolic perturbation: a zero is a real answer (touching contact), not a tie to break.
// Float evaluates the formula in double without a bound. Checked runs stages 1-3 and, beside
// them, stage 3 alone, and throws PolicyDisagreement if the two signs differ.

#include <cmath>
#include <optional>

#include "rockcontact/kernel/2d/detail/predicate_formulas.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel {

using detail::Line;

namespace detail {

// Stages 2 and 3 (predicates_staged.cpp), for calls whose filter was uncertain.
Sign cross_sign_interval_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1);
Sign crossing_side_value_sign_interval_exact(const Line& a, const Line& b, const Line& c);
// Stage 3 alone: the exact sign, the Checked policy's second opinion.
Sign cross_sign_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1);
Sign crossing_side_value_sign_exact(const Line& a, const Line& b, const Line& c);
// Throw PolicyDisagreement with the full input (predicates_staged.cpp).
[[noreturn]] void cross_sign_disagrees(const Point2& p0, const Point2& p1, const Point2& q0,
                                       const Point2& q1, Sign staged, Sign exact);
[[noreturn]] void crossing_side_disagrees(const Line& a, const Line& b, const Line& c, Sign staged,
                                          Sign exact);

inline constexpr auto double_diff = [](double a, double b) { return a - b; };

// The relative error of one floating-point operation under any IEEE rounding mode: below one
// ulp, so at most 2^-52 of the result (round to nearest halves it; the filters do not rely on
// that). Underflow is handled separately by each filter.
inline constexpr double filter_epsilon = 0x1p-52;

// Static-filter constant for the cross product, Shewchuk's ccwerrboundA with eps for u. With
// ux = fl(p1.x - p0.x), ..., left = fl(ux vy), right = fl(uy vx) and det* the exact cross
// product,
//   |det* - (left - right)| <= (3 eps + 16 eps²) (|left| + |right|)
// for the exact difference left - right of the rounded products. Derivation: each difference
// carries a relative error <= eps, each product adds eps; collecting first-order terms gives
// 3 eps per product magnitude (Shewchuk 1997, section 4.2, which uses only |rounding| <= u|x|,
// true with eps under every rounding mode), the (1 + eps)^k cross terms are below 16 eps². The
// computed det = fl(left - right) is not covered by the bound itself (its rounding adds up to
// eps |det|), but rounding is monotone in every mode and the bound is a double:
// fl(left - right) > bound implies left - right > bound, hence det* > 0, and likewise for the
// negative side, so comparing det with the bound decides the sign correctly. The bound ignores
// underflow, so the filter adds the absolute term 2^-1070, which exceeds the at most two
// subnormal roundings (2^-1074 each) of the products. tests/predicates_test.cpp re-derives
// the bound in GMP under both round-to-nearest and upward rounding.
inline constexpr double cross_error_factor = (3.0 + 16.0 * filter_epsilon) * filter_epsilon;
inline constexpr double cross_underflow_term = 0x1p-1070;

inline std::optional<Sign> cross_sign_static_filter(const Point2& p0, const Point2& p1,
                                                    const Point2& q0, const Point2& q1) {
  const double ux = p1.x - p0.x, uy = p1.y - p0.y;
  const double vx = q1.x - q0.x, vy = q1.y - q0.y;
  const double left = ux * vy;
  const double right = uy * vx;
  const double det = left - right;
  const double bound = cross_error_factor * (std::fabs(left) + std::fabs(right)) + cross_underflow_term;
  if (det > bound) return Sign::positive;
  if (-det > bound) return Sign::negative;
  // A difference of two doubles is zero exactly when they are equal (in every rounding mode),
  // so a product with a zero difference factor is exactly zero: the common axis-aligned
  // touching case needs no further stage.
  if ((ux == 0.0 || vy == 0.0) && (uy == 0.0 || vx == 0.0)) return Sign::zero;
  return std::nullopt;
}

inline Sign cross_sign_staged(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  count_call(PredicateKind::cross);
  if (const auto sign = cross_sign_static_filter(p0, p1, q0, q1)) return *sign;
  return cross_sign_interval_exact(p0, p1, q0, q1);
}

// Semi-static filter for crossing_side: the formula D A + N B evaluated in double alongside
// its magnitude T = D̄ Ā + N̄ B̄, where X̄ = |x1 y2| + |x2 y1| is the magnitude of a cross
// product of rounded differences. Derivation (eps = 2^-52, any rounding mode): Shewchuk's bound
// puts the exact difference of the two rounded products within (3 + 16 eps) eps X̄ of X, and
// rounding that difference adds eps |X~| more, so each rounded cross product X~ satisfies
// |X~ - X| <= e X̄ with e = (4 + 17 eps) eps, and |X~| <= (1 + eps)^2 X̄. Then
//   |fl(D~ A~) - D A| <= |D~| |A~ - A| + |A| |D~ - D| + eps |D~ A~| <= (9 eps + O(eps²)) D̄ Ā,
// likewise for N B, and the final sum adds eps (D̄ Ā + N̄ B̄): the error is at most
// (10 eps + O(eps²)) T. T itself is computed with a relative error of a few eps, so 11 eps T
// (one spare eps covers every second-order term) bounds the error. Underflow: if D̄, N̄, Ā, B̄
// are all at least 2^-400, the at most 2^-1074 absolute error of a subnormal product is far
// below eps T; smaller magnitudes, and overflow, are left to the interval stage.
inline constexpr double crossing_side_error_factor = 11.0 * filter_epsilon;
inline constexpr double crossing_side_min_magnitude = 0x1p-400;

struct Magnitude {
  double value = 0.0;
  double magnitude = 0.0;  // the sum of |terms| of the cross product or product that made value

  static Magnitude difference(double a, double b) {
    const double v = a - b;
    return {v, std::fabs(v)};
  }
  friend Magnitude operator*(Magnitude x, Magnitude y) {
    return {x.value * y.value, x.magnitude * y.magnitude};
  }
  friend Magnitude operator+(Magnitude x, Magnitude y) {
    return {x.value + y.value, x.magnitude + y.magnitude};
  }
  friend Magnitude operator-(Magnitude x, Magnitude y) {
    return {x.value - y.value, x.magnitude + y.magnitude};
  }
};

inline std::optional<Sign> crossing_side_semi_static(const Line& a, const Line& b, const Line& c) {
  const auto diff = [](double x, double y) { return Magnitude::difference(x, y); };
  const Magnitude d1x = diff(a.q.x, a.p.x), d1y = diff(a.q.y, a.p.y);
  const Magnitude d2x = diff(b.q.x, b.p.x), d2y = diff(b.q.y, b.p.y);
  const Magnitude d3x = diff(c.q.x, c.p.x), d3y = diff(c.q.y, c.p.y);
  const Magnitude wx = diff(b.p.x, a.p.x), wy = diff(b.p.y, a.p.y);
  const Magnitude rx = diff(a.p.x, c.p.x), ry = diff(a.p.y, c.p.y);
  const Magnitude D = d1x * d2y - d1y * d2x;
  const Magnitude N = wx * d2y - wy * d2x;
  const Magnitude A = d3x * ry - d3y * rx;
  const Magnitude B = d3x * d1y - d3y * d1x;
  const double smallest = std::fmin(std::fmin(D.magnitude, N.magnitude), std::fmin(A.magnitude, B.magnitude));
  if (!(smallest >= crossing_side_min_magnitude)) return std::nullopt;
  const Magnitude value = D * A + N * B;
  const double bound = crossing_side_error_factor * value.magnitude;
  if (!std::isfinite(bound)) return std::nullopt;
  if (value.value > bound) return Sign::positive;
  if (-value.value > bound) return Sign::negative;
  return std::nullopt;
}

// Before the interval stage: when both points of a (or of b) lie on c, decided by the cross
// product's stages, the lines are one and the crossing lies on c: the answer is zero (with c
// degenerate, a single point, d3 = 0 and the value is zero too). A filter cannot certify a
// zero, and blocks whose edges lie along one line (stacked blocks with aligned sides, faces cut
// by one joint) produce it at every step: in bench/dda_scale at 10⁴ blocks, 86 % of the exact
// fallbacks of crossing_side were a crossing on a TP edge collinear with the CP edge tested.
inline bool points_on_line(const Line& line, const Line& c) {
  return cross_sign_staged(c.p, c.q, c.p, line.p) == Sign::zero &&
         cross_sign_staged(c.p, c.q, c.p, line.q) == Sign::zero;
}

inline Sign crossing_side_value_sign_staged(const Line& a, const Line& b, const Line& c) {
  count_call(PredicateKind::crossing_side);
  if (const auto sign = crossing_side_semi_static(a, b, c)) return *sign;
  if (points_on_line(b, c) || points_on_line(a, c)) return Sign::zero;
  return crossing_side_value_sign_interval_exact(a, b, c);
}

}  // namespace detail

template <NumberPolicy Policy>
Sign cross_sign(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::cross);
    return sign_of(detail::cross_formula<double>(p0, p1, q0, q1, detail::double_diff));
  } else if constexpr (Policy::kind == PolicyKind::checked) {
    const Sign staged = detail::cross_sign_staged(p0, p1, q0, q1);
    const Sign exact = detail::cross_sign_exact(p0, p1, q0, q1);
    if (staged != exact) detail::cross_sign_disagrees(p0, p1, q0, q1, staged, exact);
    return staged;
  } else {
    return detail::cross_sign_staged(p0, p1, q0, q1);
  }
}

// Does the direction to - from lie in the upper half-circle, angle in [0, pi)? Exact under
// every policy: it compares input doubles only (a difference of doubles has the sign of their
// comparison). Used to sort edge directions by angle.
inline bool upper_half(const Point2& from, const Point2& to) {
  return to.y > from.y || (to.y == from.y && to.x > from.x);
}

template <NumberPolicy Policy>
Sign orientation(const Point2& p, const Point2& q, const Point2& r) {
  return cross_sign<Policy>(p, q, p, r);
}

// Side of the crossing point of lines a and b with respect to line c: positive when it lies
// to the left of c (c oriented from c.p to c.q). Precondition: a and b are not parallel.
template <NumberPolicy Policy>
Sign crossing_side(const Line& a, const Line& b, const Line& c) {
  const Sign denominator = cross_sign<Policy>(a.p, a.q, b.p, b.q);
  Sign value;
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::crossing_side);
    value = sign_of(detail::crossing_side_formula<double>(a, b, c, detail::double_diff));
  } else if constexpr (Policy::kind == PolicyKind::checked) {
    value = detail::crossing_side_value_sign_staged(a, b, c);
    const Sign exact = detail::crossing_side_value_sign_exact(a, b, c);
    if (value != exact) detail::crossing_side_disagrees(a, b, c, value, exact);
  } else {
    value = detail::crossing_side_value_sign_staged(a, b, c);
  }
  return value * denominator;
}

}  // namespace rockcontact::kernel
