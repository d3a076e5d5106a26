#pragma once
// The first touch of a moving node and a moving edge inside one time step: seed 003 §3, step
// (2) ("based on the geometric position of two colliding elements at times t0 and t0 + Δt,
// the collision curve L_i and point P_i can be obtained"), in the explicit CDEM engine. The
// fraction s of the step before the touch is Δt₁ / Δt, the free-motion stage of the two-scale
// contact model; the rest of the step is the contact stage.
//
// Within a step every node moves linearly from its start to its end position. With s in
// [0, 1], p(s) = p0 + s (p1 - p0) the node and a(s), b(s) the ends of a target edge (the target
// block is counter-clockwise, so its interior lies to the left of a -> b),
//
//   f(s) = (b(s) - a(s)) x (p(s) - a(s)) = A s² + B s + C,
//     e0 = b0 - a0,  de = (b1 - b0) - (a1 - a0),  r0 = p0 - a0,  dr = (p1 - p0) - (a1 - a0),
//     A = de x dr,   B = e0 x dr + de x r0,   C = e0 x r0,
//
// is negative while the node is outside (right of the edge's line). The node is within the
// edge's span when 0 <= G(s) <= E(s), G(s) = (p - a)·(b - a), E(s) = |b - a|² (both quadratics
// in s too), and λ = G / E is the touch point's position along the edge.
//
// first_touch: requires C = f(0) < 0 (the node starts strictly outside the line: a node on or
// inside it is an existing contact, the engine's business), then returns the smallest root s
// of f in (0, 1] at which the node is within the span. The cases:
//   A = 0          f is linear: one root s = -C/B, in (0, 1] iff B > 0 and f(1) = B + C >= 0
//                  (root index 2); A = B = 0 leaves f = C < 0: no touch;
//   D = B² - 4AC < 0   no real root: the node never reaches the line;
//   D = 0          a double root s* = -B/(2A): f = A (s - s*)² with A < 0 (since C < 0), so
//                  the node reaches the line at s* and turns back without crossing it (a
//                  graze). Decision: it counts as a touch, root index 0, if s* is in (0, 1]
//                  and within the span: f(s*) = 0 exactly, the node really is on the segment,
//                  and the contact stage then starts with zero normal approach (seed 003
//                  §4.2's separation criteria release it). Only an exactly zero D is a
//                  graze; the smallest positive D gives two roots;
//   D > 0          roots s₀ < s₁ (index 0, 1), tried in that order. With A > 0 only s₁ can be
//                  positive (s₀ s₁ = C/A < 0); with A < 0 both can lie in (0, 1], and then f
//                  goes back from + to - at s₁: the node re-crosses the line from its left. s₁
//                  is returned when s₀ is outside the span, as specified (the node passed the
//                  line beyond an end of the edge, and the edge met it later); whether the
//                  node then hits the target block through this edge or first through its
//                  neighbour is decided by the caller, who takes the earliest touch over the
//                  target's edges (compare_touch).
// A root at exactly s = 1 is included (the touch happens at the end of the step); s = 0 is
// excluded by C < 0.
//
// Exactness (Filtered, Exact, Checked): each input double is the exact rational it denotes,
// and every decision (C < 0, the signs of A and D, s in (0, 1], the span condition at the
// root, the order of two touches) is exact. A root is the quadratic surd s = (u + w√D) / d,
// (u, w, d) = (-B, ±1, 2A), or (-C, 0, B) for the linear case, and each decision is the sign
// of a polynomial in it; with the known-sign denominators cleared (d² > 0) that is the sign of
// α + β√D, α and β polynomials of the input (at most degree 6), and comparing the roots of two
// different quadratics is the sign of x + y√D_x + z√D_y. The signs are decided by squaring
// (touch_time.cpp), so no division, no root is ever computed exactly: the exact stage is a ring
// evaluation in CGAL::Mpzf, as in the predicates' engine (kernel/core/detail/staged_sign.hpp).
//
// Staged evaluation, the "filtered root isolation" of the design:
//   1. interval: the coefficients and every decision in CGAL::Interval_nt_advanced under one
//      upward-rounding switch, square roots by interval sqrt; a decision is certain when its
//      interval excludes zero (or is the point zero). compare_touch encloses both roots in
//      intervals (the cancellation-free form of the quadratic formula) and is certain when the
//      enclosures are disjoint;
//   2. exact: each decision the interval left uncertain, and only that one, redone in Mpzf.
// There is no double filter in front: the interval stage is already a handful of operations
// per decision. Nothing is counted in predicate_stats.hpp (the touch time has no
// PredicateKind; one would be added there if its fallbacks are to be measured).
//   Float     the same coefficients in plain double, the cancellation-free quadratic formula,
//             comparisons in double: no guarantee, the baseline a plain DEM code would use.
//             compare_touch<Float> compares the rounded s values.
//   Filtered  stages 1-2.
//   Exact     stage 2 for every decision.
//   Checked   Filtered and Exact side by side; PolicyDisagreement (with the full input as
//             hexadecimal floats) if the decisions differ: whether there is a touch, which
//             root, the sign of a comparison. The rounded values are Filtered's.
//
// Rounded outputs (s and λ as doubles), independent of the FPU rounding mode:
//   Exact     s and λ correctly rounded: the double nearest to the exact value, ties to even
//             (|s' - s| <= 2^-53 s, |λ' - λ| <= 2^-53 λ), found by bisecting the doubles of the
//             interval enclosure with exact comparisons sign(s - x) (a surd sign again).
//   Filtered  the midpoint of the interval enclosure when it certifies
//               |s' - s| <= touch_time_tolerance · s   and   |λ' - λ| <= touch_time_tolerance,
//             else correctly rounded as under Exact. (λ's bound is absolute: λ is a fraction
//             of the edge's length, and an exact end-point touch has λ = 0.)
//   Checked   as Filtered.
//   Float     plain double, no bound; s in (0, 1] and λ clamped to [0, 1].
//
// Preconditions: finite coordinates; the edge keeps a positive length over the step (a block's
// edge does not collapse: if b(s) = a(s) at a root, f(s) = 0 and the span test reads 0 <= 0
// <= 0, so the collapsed edge counts as touched, with λ = 0).
// kernel/2d/tests/touch_time_test.cpp checks an analytic touch (seed 003's 1 m gap closed at
// 3 m/s), rotating edges with two roots, the order of two vertices of a spinning block 1.5e-12 s
// apart and 2e-18 of a step apart (below the resolution of a rounded s), and Filtered against
// Exact on random and degenerate motions.

#include <optional>

#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel {

// Filtered's certified accuracy of the rounded touch: relative on s, absolute on λ
// (dimensionless). Smaller values send more touches to the exact rounding (a bisection of the
// enclosure's doubles, ~10 exact comparisons for a moderately wide enclosure, ~60 at most).
// The enclosure of s is a few dozen ulps wide on well-conditioned input, so 2^-44 (256 ulps)
// refuses it only after cancellation: a node and an edge moving together ~100 times faster
// than they approach each other (the relative motion dr = dp - da keeps the absolute error of
// dp), or near a double root, where √D amplifies the width. On random crossings with edges
// turning by up to 5 % of their length, 1 touch in 300 is rounded exactly.
inline constexpr double touch_time_tolerance = 0x1p-44;

struct MovingPoint2 {
  Point2 start;  // position at the start of the step, metres
  Point2 end;    // position at the end of the step, metres; linear motion in between
};

// A node of the main block and an edge a -> b of the target block, the target's interior on
// the left of a -> b.
struct NodeEdgeMotion {
  MovingPoint2 node, a, b;
};

// Which root of f a touch is (TouchTime::root).
inline constexpr int touch_root_smaller = 0;  // the smaller root of a quadratic (or its double root)
inline constexpr int touch_root_larger = 1;   // the larger root of a quadratic
inline constexpr int touch_root_linear = 2;   // the root -C/B of a linear f (A = 0)

struct TouchTime {
  double s = 0;       // the touch instant as a fraction of the step, in (0, 1], rounded (bounds above)
  double lambda = 0;  // where on the edge at s: (p - a)·(b - a) / |b - a|², in [0, 1], rounded
  int root = 0;       // internal: which root of f (touch_root_*), for compare_touch's exact comparison
};

// The first s in (0, 1] at which the node reaches the closed segment [a(s), b(s)] coming from
// outside (see the header comment for the cases), or nullopt: f(0) >= 0 (already on or inside
// the edge's line at the start of the step) or no root of f in (0, 1] within the span.
template <NumberPolicy P>
std::optional<TouchTime> first_touch(const NodeEdgeMotion& m);

// The exact sign of s_x - s_y for two touches tx, ty found by first_touch<P> (the same P) on
// motions x, y: negative when x touches first. Exact under Filtered, Exact and Checked, also
// when the rounded s values are equal; under Float the sign of tx.s - ty.s.
template <NumberPolicy P>
Sign compare_touch(const NodeEdgeMotion& x, const TouchTime& tx, const NodeEdgeMotion& y,
                   const TouchTime& ty);

}  // namespace rockcontact::kernel
