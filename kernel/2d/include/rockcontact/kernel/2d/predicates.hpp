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
// Three stages, as in CGAL's filtered kernel and geogram's PCK:
//   1. filter: the formula in double with a proven error bound; answers when |value| > bound
//      (cross: a static bound, then a check that no operation rounded at all, which settles
//      most exact touches; crossing_side: a semi-static bound, then a running error bound,
//      then a check that a or b is c's own line, which settles the crossings on collinear edges);
//   2. exact:  the same formula in GMP rationals (kernel/2d/src/predicates_exact.cpp);
//   3. no symbolic perturbation: a zero is a real answer (touching contact), not a tie to break.
// The Float policy stops after evaluating stage 1's value without the bound; the Exact policy
// goes straight to stage 2.

#include <cmath>
#include <optional>

#include "rockcontact/kernel/core/detail/error_bounded.hpp"
#include "rockcontact/kernel/2d/detail/predicate_formulas.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel {

using detail::Line;

namespace detail {

Sign cross_sign_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1);
Sign crossing_side_value_sign_exact(const Line& a, const Line& b, const Line& c);

inline constexpr auto double_diff = [](double a, double b) { return a - b; };

// Static-filter constant for the cross product, Shewchuk's ccwerrboundA. With ux = fl(p1.x -
// p0.x), ..., left = fl(ux vy), right = fl(uy vx) and det* the exact cross product,
//   |det* - (left - right)| <= (3u + 16u²) (|left| + |right|)
// for the exact difference left - right of the rounded products. Derivation (u = 2^-53): each
// difference carries a relative error <= u, each product adds u; collecting first-order terms
// gives 3u per product magnitude (Shewchuk 1997, section 4.2), the
// (1 + u)^k cross terms are below 16u². The computed det = fl(left - right) is not covered by
// the bound itself (its rounding adds up to u |det|), but rounding is monotone and the bound
// is a double: fl(left - right) > bound implies left - right > bound, hence det* > 0, and
// likewise for the negative side, so comparing det with the bound decides the sign correctly.
// The bound ignores underflow, so the filter adds the absolute term 2^-1070, which exceeds the
// at most two subnormal roundings (2^-1075 each) of the products. tests/predicates_test.cpp
// re-derives the bound in GMP.
inline constexpr double cross_error_factor = (3.0 + 16.0 * unit_roundoff) * unit_roundoff;
inline constexpr double cross_underflow_term = 0x1p-1070;

// Stage 1b for the cross product, before GMP: when the four differences and the two products
// were all computed without rounding error, left - right is the exact determinant and comparing
// left with right gives its sign. This settles most exact touches (e.g. two parallel edges with
// bitwise-equal difference vectors), which the filter cannot certify as zero. The rounding
// error of a difference is found by Knuth's two-sum, that of a product by fma (a correctly
// rounded fused multiply-add returns it exactly); both are exact in IEEE double.
inline bool difference_is_exact(double a, double b, double difference) {
  const double b_virtual = a - difference;
  const double a_virtual = difference + b_virtual;
  return (a - a_virtual) + (b_virtual - b) == 0.0;
}

inline std::optional<Sign> cross_sign_exact_in_double(const Point2& p0, const Point2& p1,
                                                      const Point2& q0, const Point2& q1,
                                                      double ux, double uy, double vx, double vy,
                                                      double left, double right) {
  if (!difference_is_exact(p1.x, p0.x, ux) || !difference_is_exact(p1.y, p0.y, uy) ||
      !difference_is_exact(q1.x, q0.x, vx) || !difference_is_exact(q1.y, q0.y, vy)) {
    return std::nullopt;
  }
  // The error of a product is representable (so fma returns it exactly) only when the product
  // is far enough from the subnormal range; closer to it, or on overflow, go to GMP.
  const auto product_is_exact = [](double a, double b, double product) {
    if (a == 0.0 || b == 0.0) return true;
    return std::isfinite(product) && std::fabs(product) >= 0x1p-960 && std::fma(a, b, -product) == 0.0;
  };
  if (!product_is_exact(ux, vy, left) || !product_is_exact(uy, vx, right)) return std::nullopt;
  return left > right ? Sign::positive : (left < right ? Sign::negative : Sign::zero);
}

inline Sign cross_sign_filtered(const Point2& p0, const Point2& p1, const Point2& q0,
                                const Point2& q1) {
  count_call(PredicateKind::cross);
  const double ux = p1.x - p0.x, uy = p1.y - p0.y;
  const double vx = q1.x - q0.x, vy = q1.y - q0.y;
  const double left = ux * vy;
  const double right = uy * vx;
  const double det = left - right;
  const double bound = cross_error_factor * (std::fabs(left) + std::fabs(right)) + cross_underflow_term;
  if (det > bound) return Sign::positive;
  if (-det > bound) return Sign::negative;
  // A difference of two doubles is zero exactly when they are equal, so a product with a zero
  // difference factor is exactly zero: the common axis-aligned touching case needs no GMP.
  if ((ux == 0.0 || vy == 0.0) && (uy == 0.0 || vx == 0.0)) return Sign::zero;
  if (const auto sign = cross_sign_exact_in_double(p0, p1, q0, q1, ux, uy, vx, vy, left, right)) {
    return *sign;
  }
  count_fallback(PredicateKind::cross);
  return cross_sign_exact(p0, p1, q0, q1);
}

// Semi-static filter for crossing_side (stage 1a): the formula D A + N B evaluated in double
// alongside its magnitude T = D̄ Ā + N̄ B̄, where X̄ = |x1 y2| + |x2 y1| is the magnitude of a
// cross product of rounded differences. Derivation (u = 2^-53): Shewchuk's bound puts the exact
// difference of the two rounded products within (3 + 16u) u X̄ of X, and rounding that
// difference adds u |X~| more, so each rounded cross product X~ satisfies |X~ - X| <= e X̄ with
// e = (4 + 17u) u, and |X~| <= (1 + u)^2 X̄. Then
//   |fl(D~ A~) - D A| <= |D~| |A~ - A| + |A| |D~ - D| + u |D~ A~| <= (9u + O(u²)) D̄ Ā,
// likewise for N B, and the final sum adds u (D̄ Ā + N̄ B̄): the error is at most
// (10u + O(u²)) T. T itself is computed with a relative error of a few u, so 11u T (one spare u
// covers every second-order term) bounds the error. Underflow: if D̄, N̄, Ā, B̄ are all at least 2^-400, the at most 2^-1074 absolute error of a
// subnormal product is far below u T; smaller magnitudes, and overflow, go to the running-error
// filter (stage 1b), which handles both.
inline constexpr double crossing_side_error_factor = 11.0 * unit_roundoff;
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

// Stage 1c for crossing_side, before GMP: when both points of a (or of b) lie on c, decided by
// the cross product's filter, the lines are one and the crossing lies on c: the answer is zero
// (with c degenerate, a single point, d3 = 0 and the value is zero too). The filters cannot
// certify a zero, and blocks whose edges lie along one line (stacked blocks with aligned sides,
// faces cut by one joint) produce it at every step: in bench/dda_scale at 10⁴ blocks, 86 % of
// the GMP fallbacks of crossing_side were a crossing on a TP edge collinear with the CP edge
// tested, and GMP was 23 % of the step's instructions.
inline bool points_on_line(const Line& line, const Line& c) {
  return cross_sign_filtered(c.p, c.q, c.p, line.p) == Sign::zero &&
         cross_sign_filtered(c.p, c.q, c.p, line.q) == Sign::zero;
}

inline Sign crossing_side_value_sign_filtered(const Line& a, const Line& b, const Line& c) {
  count_call(PredicateKind::crossing_side);
  if (const auto sign = crossing_side_semi_static(a, b, c)) return *sign;
  const ErrorBounded value =
      crossing_side_formula<ErrorBounded>(a, b, c, [](double x, double y) {
        return ErrorBounded::difference(x, y);
      });
  if (const auto sign = certain_sign(value)) return *sign;
  if (points_on_line(b, c) || points_on_line(a, c)) return Sign::zero;
  count_fallback(PredicateKind::crossing_side);
  return crossing_side_value_sign_exact(a, b, c);
}

}  // namespace detail

template <NumberPolicy Policy>
Sign cross_sign(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::cross);
    return sign_of(detail::cross_formula<double>(p0, p1, q0, q1, detail::double_diff));
  } else if constexpr (Policy::kind == PolicyKind::filtered) {
    return detail::cross_sign_filtered(p0, p1, q0, q1);
  } else {
    detail::count_call(PredicateKind::cross);
    return detail::cross_sign_exact(p0, p1, q0, q1);
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
  } else if constexpr (Policy::kind == PolicyKind::filtered) {
    value = detail::crossing_side_value_sign_filtered(a, b, c);
  } else {
    detail::count_call(PredicateKind::crossing_side);
    value = detail::crossing_side_value_sign_exact(a, b, c);
  }
  return value * denominator;
}

}  // namespace rockcontact::kernel
