#pragma once
// The coordinates of a line-line crossing: the construction of an IP vertex "CP edge (p, q) x
// TP edge (t0, t1)", once the exact predicates have decided that the crossing exists and lies
// on the TP segment.
//
//   X = t0 + s (t1 - t0),   s = N / D,   N = l x w,  D = l x d,
//   l = q - p,  d = t1 - t0,  w = p - t0.
//
// The crossing of two nearly parallel lines is ill-conditioned: in double, N and D each carry
// an error of a few ulps of their magnitudes N̄ = |lx wy| + |ly wx|, D̄ = |lx dy| + |ly dx|, so s
// is off by about u (N̄ + D̄) / |D| ~ u / sin(angle) and X slides along the TP edge by that times
// |d|. At a 1e-13 rad angle that is a slide of 1e-3 |d|, and a slide is not harmless: where the
// crossing coincides with a CP vertex (a CP edge lying along a TP edge to within rounding), the
// slid vertex leaves the next IP edge's line and cuts a triangle of area ~ slide x edge length
// off the IP, a first-order error in the area and the force.
//
// So under Filtered the construction is filtered like a predicate:
//   1. s in double, with the certified bound ds on |s' - s| derived below;
//   2. if ds <= crossing_parameter_tolerance (2^-40), X in double;
//   3. otherwise X exact (GMP rationals) and each coordinate rounded to the nearest double.
// Result, per coordinate c:
//   |X'_c - X_c| <= (2^-40 + 3u) |t1_c - t0_c| + 2u |X_c| + 2^-1073      (u = 2^-53)
// i.e. within ~1e-12 of the TP edge's extent, whatever the angle; an exactly rounded point
// (error <= u |X_c|) whenever the lines are within ~1e-3 rad of parallel. Fallbacks are counted
// as PredicateKind::crossing_point.
//
// Derivation of ds (round to nearest, |s| <= 1 because the exact predicates put X on the TP
// segment): Shewchuk's bound (3 + 16u) u N̄ covers the exact difference of the two rounded
// products, and rounding that difference adds u |N'| <= u (1 + u) N̄ more; with N̄ itself
// computed (a factor (1 - u)^2 low at most), e = (4 + 32u) u gives |N' - N| <= e N̄ + 2^-1074
// and |D' - D| <= e D̄ + 2^-1074 for the double cross products of rounded differences (the
// absolute term covers the two products' subnormal roundings, 2^-1075 each), and
//   N'/D' - N/D = (N' - N) / D' - (N/D) (D' - D) / D',
// so |N'/D' - s| <= (e (N̄ + D̄) + 2^-1073) / |D'|; the division adds u |s'| + 2^-1074. The
// bound is evaluated in double from non-negative terms, so it is under-estimated by at most a
// factor (1 - u)^8, which the factor (1 + 2^-40) applied to it covers. A non-finite value or
// bound (overflow, D' = 0) takes the exact path. The point adds, per coordinate,
//   |fl(t0_c + fl(s' fl(d_c))) - (t0_c + s' d_c)| <= (2u + u^2) |d_c| + u |X'_c| + 2^-1074.
//   Float     X in double, no bound (what a plain DEM code does); s clamped to [0, 1].
//   Exact     X exact, each coordinate rounded to nearest.
//   Checked   as Filtered (Checked compares signs; a construction has no single right double).
// The construction rounds to nearest, the mode of all the library's double code.
// kernel/2d/tests/crossing_point_test.cpp re-derives the bound against GMP on near-parallel input.

#include <optional>

#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

// The filter's tolerance on the parameter s along the TP edge (dimensionless). Smaller values
// make Filtered's crossings more accurate and send more near-parallel crossings to GMP
// (~2 us each): at 2^-40 it is the crossings within ~1e-3 rad of parallel, about 6 in 10^4
// crossings of random pairs.
inline constexpr double crossing_parameter_tolerance = 0x1p-40;

// The crossing of line (p, q) with segment (t0, t1) under Policy, coordinates in metres,
// relative to `origin`: X - origin, computed as (t0 - origin) + s (t1 - t0), so that a frame
// near the pair keeps the digits a crossing 10^6 m from the origin would lose (the bound below
// holds with X_c replaced by X_c - origin_c, plus u |t0_c - origin_c| for the shift). Under
// Exact, X - origin is exact and rounded once. Precondition: the lines are not parallel and
// the crossing lies on the segment (decided by exact predicates on the given coordinates).
template <NumberPolicy Policy>
Point2 construct_crossing_point(const Point2& p, const Point2& q, const Point2& t0, const Point2& t1,
                                const Point2& origin = {0.0, 0.0});

namespace detail {

// Stages 1-2 alone: the double crossing when its certified parameter error is at most
// `tolerance`, else nullopt. Exposed for the test that re-derives the bound.
struct CertifiedCrossing {
  Point2 point;
  double parameter_error;  // the certified bound ds on |s' - s|
};
std::optional<CertifiedCrossing> crossing_in_double(const Point2& p, const Point2& q, const Point2& t0,
                                                    const Point2& t1, double tolerance,
                                                    const Point2& origin = {0.0, 0.0});

}  // namespace detail

}  // namespace rockcontact::kernel
