#pragma once
// The overlap verdict of two convex polyhedra: separate, touch or overlap (core/overlap.hpp),
// exact under Filtered, Exact and Checked.
//
// Method: separating planes among the facet normals of the Minkowski difference B - A. Two
// convex polyhedra have disjoint interiors exactly when some plane separates them weakly (A on
// one closed side, B on the other), and are disjoint exactly when some plane separates them
// strictly; in both cases a facet of B - A supplies one, and its normal is the outward normal of
// a face of A, the inward normal of a face of B, or the cross product of a non-parallel edge of A
// and edge of B. So:
//   * face of A (CCW from outside, vertices f0 f1 f2): B lies on or above its plane when
//     orient3d(f0, f1, f2, b) >= 0 for every vertex b of B, strictly when > 0; likewise with
//     A and B exchanged;
//   * edge e of A and edge f of B, not parallel: the plane through e parallel to f and the plane
//     through f parallel to e, both with normal n = e x f, support A and B on opposite sides
//     when triple(e, f, e0 -> a) has one sign (or zero) over A, triple(e, f, f0 -> b) the other
//     over B; the gap between the two planes along the side of B is then sign_B *
//     triple(e, f, e0 -> f0);
//   * separate if some candidate gives a strictly positive gap, touch if none does but some
//     gives a zero gap, overlap otherwise.
// Every decision is a sign of a degree-3 polynomial of input coordinates (predicates.hpp);
// nothing is constructed. Cost O(F_A V_B + F_B V_A + E_A E_B (V_A + V_B)) predicates, with an
// early exit on the first strict separation and on the first vertex on the wrong side of a
// candidate.

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/overlap.hpp"

namespace rockcontact::kernel {

template <NumberPolicy Policy>
Overlap classify_overlap(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

}  // namespace rockcontact::kernel
