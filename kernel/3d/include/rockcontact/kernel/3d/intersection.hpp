#pragma once
// The intersection polyhedron of two convex polyhedra and its volume.
//
// intersection<P>(a, b) clips a by every face plane of b in turn (plane_cut.hpp): A ∩ B is the
// part of A below all of B's face planes. Every decision is an exact sign under Filtered, Exact
// and Checked (orient3d on input points, the three-plane side on implicit vertices), all taken
// before anything is constructed. A clip that leaves no interior
// returns the empty polyhedron, so the result is empty exactly when the interiors of a and b
// are disjoint (separate or touching: the contact set of a touching pair is not represented),
// and is A ∩ B otherwise. The clipping stops at the first empty result.
//
// intersection_volume<P>(a, b) is the volume of that polyhedron (HalfspacePolyhedron::volume:
// double in a local frame under Float; under Filtered and Checked within 2^-31 |V| or 2^-41 s^3
// of the exact volume V, s the largest extent of the pair's bounding box; the exact rational
// volume rounded once under Exact), 0 unless the interiors overlap.

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

template <NumberPolicy Policy>
HalfspacePolyhedron intersection(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

// Cubic metres.
template <NumberPolicy Policy>
double intersection_volume(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

}  // namespace rockcontact::kernel
