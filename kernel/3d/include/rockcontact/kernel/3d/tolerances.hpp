#pragma once
// Every tolerance of the 3D kernel, with its unit and its effect. Predicates are exact, so no
// tolerance decides a combinatorial question about a valid block; what remains is how far input
// may stray from the model before it is refused.

namespace rockcontact::kernel {

// A face whose vertices are not exactly coplanar is accepted when each of them lies within
// this fraction of the block's size (the largest extent of its bounding box) from the face's
// mean plane, and is then split into exactly planar facets by the exact convex hull
// (convex_polyhedron.hpp). Rotating a block, deforming it by a strain or rounding the implicit
// vertices of a cut block moves a vertex off its face's plane by a few ulps of the block's
// coordinates, 1e-16 relative for a block near the origin and up to 1e-10 relative for a 1 m
// block 10^6 m from it; 1e-9 accepts all of that while a face bent on purpose, or given with
// a wrong vertex, is refused. Dimensionless. A larger value accepts visibly bent faces, whose
// split the user may not expect; a smaller one refuses far-from-origin rotated blocks.
inline constexpr double face_planarity_tolerance = 1e-9;

// The penetration plane of two overlapping parts (contact_constraints.hpp, step 4) is built in
// double: its normal (penetration.hpp) is within a few units of 2^-53 / sin a of the exact one
// (a the angle of an edge pair), and the heights and gaps measured along it within a few ulps
// of the pair's size S. This fraction of S (the largest distance of a vertex of the pair from
// cp's first vertex) absorbs that when a constraint is compared with the depth, two constraints
// are taken for one position on the plane, or a vertex is taken for a support vertex: 1e-10 S
// is 1e-10 m on a 1 m pair, far above the rounding (1e-13 S for edges 1e-3 rad from parallel)
// and far below any physical penetration. Dimensionless. Larger merges distinct contact
// positions; smaller lets rounding drop a crossing exactly as deep as the pair.
inline constexpr double penetration_slack = 1e-10;

// Two constraints of one block pair are one contact (contact_constraints.hpp, step 5) when their
// unit normals agree within this (1 - cos of the angle: 1e-9 is 4.5e-5 rad) and their points
// within this fraction of the pair's size. The parts of a cut block meet only to the rounding of
// their implicit vertices (1e-16 relative, up to 1e-10 far from the origin), so their shared
// planes and vertices agree far inside it, while two real contacts are never that close.
// Dimensionless. Larger merges nearby contacts; smaller counts a shared vertex twice.
inline constexpr double same_contact_tolerance = 1e-9;

}  // namespace rockcontact::kernel
