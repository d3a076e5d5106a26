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

// Two faces of cut blocks are one shared face, to rounding, when merging small blocks asks how
// much face two blocks share (block_cutting.hpp): their outward unit normals are opposite within
// this (1 + n_a . n_b; 1e-9 is 4.5e-5 rad) and every vertex of one lies within this fraction of
// the blocks' size S (the largest extent of their bounding box) of the other's plane; a shared
// area of at most this times S² is none (an edge or a vertex met to rounding, a strip at most
// this times S wide and S long). The faces of neighbouring pieces are made of the same rounded
// vertices and the same exact plane, so they agree to a few ulps of the coordinates (1e-16
// relative near the origin, 1e-10 for a 1 m scene 10^6 m from it), and each is planar within
// face_planarity_tolerance of its block's size, which is smaller than S. Dimensionless. Larger
// takes faces a few degrees or millimetres apart for one; smaller lets a face 10^7 m from the
// origin miss its neighbour.
inline constexpr double shared_face_tolerance = 1e-9;

// A vertex off the feature of the other block it meets by no more than this fraction of the
// pair's extent is on it but for rounding (contact_constraints.hpp, step 3): its candidate
// planes are checked with cone_flush_sine, as at an exact touch, while its gap stays the exact
// distance. A block moved along the face or edge it rests on (a wedge sliding along its line of
// intersection) has its vertices off that feature by a few ulps of their coordinates (1e-16
// relative near the origin, 1e-14 after 10^4 steps of rounding); exactly, no plane then passes,
// and the normal would be the line to the feature, 1e-16 long. Dimensionless. Larger takes
// truly separated near pairs (the reference pairs go down to 7e-10 of their size) for touching
// ones; smaller misses rounded touches.
inline constexpr double coincidence_tolerance = 1e-12;

// The sine of the angle within which a direction counts as lying in a plane when the kernel
// asks which side of a contact plane a block's tangent cone is on (contact_constraints.hpp, steps
// 2 and 3): the no-overlap check of a candidate plane and the supporting sides of an edge pair.
// Faces meant to be coplanar are not exactly so once blocks move: the rotation of a step rounds
// their vertices (1e-16 relative), and a block resting on its penalty springs tilts by its
// settling over its size (1e-6 to 1e-4 rad at the usual kn). Exactly, the tilted face then
// crosses the plane of the face it rests on, no candidate plane of a vertex on an edge passes,
// and coplanar edges crossing at a corner of the contact polygon do not support their blocks: a
// wedge sliding along its joints lost the corners of its contact polygons this way. 2^-10
// (about 1e-3 rad, 0.056 degrees) is ten times the largest settling tilt and far below the 1-3
// degrees a contact plane may turn in a step (seed 001 §5.2); a power of two, so that its square
// is exact in the exact test. Dimensionless. Larger takes truly crossing cones for touching ones;
// smaller lets settled blocks lose contacts again.
inline constexpr double cone_flush_sine = 0x1p-10;

}  // namespace rockcontact::kernel
