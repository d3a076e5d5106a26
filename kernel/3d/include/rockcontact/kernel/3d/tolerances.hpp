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

}  // namespace rockcontact::kernel
