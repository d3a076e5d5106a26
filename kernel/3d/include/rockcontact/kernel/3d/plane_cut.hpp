#pragma once
// Clipping a convex polyhedron by a plane, and cutting it in two.
//
// clip<P>(p, plane) is the part of p on the closed side below the plane (opposite the normal);
// cut_by_plane<P>(p, plane) gives both parts {below, above}. Method:
//   1. classify every vertex of p against the plane: side_of_plane (plane.hpp) on the input
//      point (orient3d, with its static filter) or on the three planes of an implicit vertex:
//      exact signs under Filtered, Exact and Checked, never a rounded coordinate;
//   2. no vertex strictly below: the part below has no interior and clip returns the empty
//      polyhedron (p only touches the plane in a vertex, an edge or a face, or lies above);
//      no vertex strictly above: clip returns p unchanged (a vertex, edge or face of p on the
//      plane stays as it is);
//   3. otherwise each face with a vertex strictly below keeps its vertices on or below the
//      plane, in order, and gains a new implicit vertex on each edge whose ends lie strictly on
//      opposite sides: the meeting point of the edge's two face planes and the cutting plane
//      (one vertex per edge, shared by both faces). Faces without a vertex strictly below are
//      dropped (what remains of them lies in the plane);
//   4. the new face on the cutting plane: each kept face has at most two vertices on the plane
//      (it is strictly convex), and when it has two, they are consecutive in its loop, x -> y,
//      an edge of the section; the new face, normal along the plane's, traverses it y -> x, and
//      these edges chain into its loop. Its order comes from this topology, never from sorting
//      rounded points.
// Degenerate cuts therefore give closed, valid polyhedra: a vertex on the plane is shared by the
// pieces, a face on the plane becomes a face of one piece, a plane that only touches p gives
// p and the empty polyhedron. The empty polyhedron is returned for every result without
// interior (the lower-dimensional set p ∩ plane is not represented).
// Cost: one predicate per vertex, O(V + E) work plus a linear search among the k new vertices
// for each cut edge (O(k^2), k the size of the section); no construction.

#include <utility>

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"
#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

template <NumberPolicy Policy>
HalfspacePolyhedron clip(const HalfspacePolyhedron& p, const Plane3& plane);

// {below, above}: clip(p, plane) and clip(p, plane.opposite()), classifying the vertices once.
template <NumberPolicy Policy>
std::pair<HalfspacePolyhedron, HalfspacePolyhedron> cut_by_plane(const HalfspacePolyhedron& p,
                                                                   const Plane3& plane);

}  // namespace rockcontact::kernel
