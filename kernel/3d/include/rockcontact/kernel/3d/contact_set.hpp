#pragma once
// The contact set of two touching convex polyhedra: the closed set a ∩ b, a point, a segment or
// a convex polygon, as its corners (for parallel edge-edge, edge-face and face-face contacts,
// the "boundary vertices of the overlapping polygon" that seed 001 §1 uses as contact
// positions).
//
// Whether the pair touches (meets, interiors disjoint) is decided exactly by classify_overlap
// (overlap.hpp) under Filtered, Exact and Checked; the result is nullopt unless it does.
//
// Method. A touching pair has a candidate separating plane with zero gap
// (detail/separating_plane.hpp): a face plane of a or b, or the plane through an edge of a
// parallel to an edge of b. a lies on one closed side of it and b on the other, so
// a ∩ b = (a ∩ plane) ∩ (b ∩ plane), and each block meets a supporting plane in a feature: a
// vertex, an edge or a face, whose vertices are exactly the block's vertices on the plane
// (orient3d or the edge-edge triple product zero, exact). The two coplanar convex features are
// intersected in the plane:
//   * 2D orientation of three coplanar input points p, q, r: the sign of the component along a
//     coordinate axis k of (q - p) x (r - p), i.e. triple_sign(p, q, p, r, 0, e_k) on input
//     coordinates, exact; it is the in-plane orientation times the fixed sign of the plane
//     normal's k-th component, which must be non-zero (checked exactly). Only whether two such
//     signs agree is used, so that fixed factor never matters. k is the normal's dominant axis
//     as estimated in double (it only conditions the constructions below).
//   * corners of the intersection: the vertices of each feature that lie in the other (a
//     vertex of a convex set inside another convex set is a corner of their intersection), a
//     vertex shared by both counted once (input points compare exactly), and the crossings of an
//     edge of one feature with an edge of the other where each strictly separates the other's
//     endpoints (a proper crossing lies inside one edge of each feature, where the intersection
//     is locally a wedge: a corner, and no other crossing or vertex is at the same point). These
//     are all the corners and nothing else, so there are no duplicates and no collinear extras;
//     1, 2 or >= 3 of them give dimension 0, 1 or 2.
// Every decision is an exact sign on input coordinates under the staged policies; only the
// crossings are constructed: p + t (q - p) with t the ratio of two 2D cross products in the
// projection along k, in double in a local frame (within a few units of 2^-53 S / sin of the
// projected crossing angle, S the features' extent), or in exact rationals rounded once under
// Exact; measured on the contact3d reference: every corner within 1.1e-16 S of the exact one
// (tests/contact_set_test.cpp). Corners are listed in no particular order (ordering a polygon's
// symbolic corners exactly would need predicates on crossings, which the kernel lacks yet).

#include <optional>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

struct ContactSet {
  int dimension;                 // 0 point, 1 segment, 2 convex polygon
  std::vector<Point3> vertices;  // the set's corners (1, 2 or >= 3), metres, in no particular order
};

template <NumberPolicy Policy>
std::optional<ContactSet> contact_set(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

}  // namespace rockcontact::kernel
