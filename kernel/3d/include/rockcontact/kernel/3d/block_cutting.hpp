#pragma once
// Block cutting in 3D: the blocks that persistent joint sets cut out of a region, by successive
// exact plane cuts of convex polyhedra (DESIGN.md, "Block cutting").
//
// A joint set is a family of parallel planes given as geologists give them (seed 001 §6.1):
// dip δ in [0, 90] degrees, dip direction α in [0, 360) degrees clockwise from North, spacing
// and offset in m. Axes x East, y North, z Up. Its planes are
//     n . p = offset + k spacing   (k an integer),   n = (sin δ sin α, sin δ cos α, cos δ),
// n the upward unit normal (the dip vector, pointing down the slope of the plane, is
// (cos δ sin α, cos δ cos α, -sin δ)). Angles that are multiples of 90 degrees use exact sines
// and cosines, so horizontal and vertical joints are exactly axis-aligned. Each plane is then
// exactly the plane of its double coefficients (n rounded, offset + k spacing rounded): every
// piece is bounded by exactly these planes, so the pieces tile the region exactly.
//
// cut_by_joint_sets, step by step:
//   1. Validate the sets (each message names "joint_sets[i].FIELD") and bound the work: the
//      planes of a set that can meet a part (within its extent along n, one more on each side)
//      number at most max_cut_planes in all, and the pieces at most max_cut_pieces.
//   2. Each region part (a convex polyhedron) becomes a HalfspacePolyhedron; each set cuts every
//      current piece by its planes in increasing k (plane_cut.hpp: the sides of the implicit
//      vertices are exact signs, so no piece is lost or duplicated, whatever the degeneracy: a
//      plane through a vertex, along an edge or on a face). A piece records its part and its
//      cell, the k of the slab it lies in for every set.
// cut_region then rounds each piece's vertices to doubles into a ConvexPolyhedron: the exact
// point rounded once, coordinate by coordinate, to the nearest double (vertex_coordinates<Exact>,
// whatever the policy of the cut), so a vertex that several pieces share is the same double in
// each and blocks that touch at the cut meet exactly there (a simulation then sees contacts at
// exact touch, not gaps and overlaps of a few ulps whose contact planes rounding decides). The
// faces are planar only to rounding, which ConvexPolyhedron accepts within
// face_planarity_tolerance. Pieces of the same cell from different parts of a
// non-convex region that meet face to face (a two-dimensional contact set) form one block,
// given as its convex parts; the blocks are ordered by their first piece. Last,
// merge_small_blocks merges the blocks below options.min_block_volume into a neighbour.
//
// merge_small_blocks, the 3D counterpart of the 2D cut's step 5 (2d/block_cutting.hpp): a cut
// leaves slivers beside blocks a thousand times their size, a few centimetres thick, and such a
// sliver squeezed between its neighbours sets the time step of a whole simulation. Only when
// min_block_volume > 0:
//   1. A block's volume is the sum of its parts' (moments.hpp, on the rounded parts, in double).
//      The blocks below min_block_volume (fragments) are processed smallest volume first, ties
//      lower index (the order above) first.
//   2. The face area two blocks share is summed over every pair of their parts' faces (as given)
//      that lie on one plane with opposite outward normals, to rounding (shared_face_tolerance,
//      tolerances.hpp, of S, the largest extent of the bounding box of all the blocks): the area
//      of the intersection of the two convex face polygons, both projected along the axis of the
//      normal's largest component, one clipped by the other (Sutherland-Hodgman), its shoelace
//      area divided by that component of the unit normal. A sum of at most
//      shared_face_tolerance S² counts as none (an edge or a vertex met to rounding). The pieces
//      come from exact plane cuts with their vertices rounded once, so the faces two neighbours
//      share coincide to rounding and their area is the shared face's to rounding.
//   3. A fragment merges into the block it shares the largest area with (ties, equal doubles, to
//      the lower index): the fragment's parts are appended to the neighbour's, and the merged
//      block takes the neighbour's place and its volume the sum. The neighbour is at least as
//      large as the fragment (every other block below the bound is, being processed later, and
//      the rest are above it), so the merged block keeps the place of the larger of the two. It
//      is processed again while still below the bound.
//   4. A fragment that shares no face with any block stays as it is; merges only join blocks, so
//      it never gains a neighbour later.
//   5. The blocks left are numbered from 1 again in their order: a block's number drops by one
//      for every fragment before it that merged.
// A merged block is one body given as convex parts that meet face to face, the form the 3D
// engine takes non-convex blocks in. With min_block_volume > 0, every block's volume (as step 1
// computes it) is >= min_block_volume unless it has no neighbour. The blocks still tile the
// region: a merge only regroups parts.
//
// Volume is conserved exactly: the pieces' exact volumes (HalfspacePolyhedron under Exact) sum
// to the region's. The rounded blocks conserve it to rounding.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"
#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/core/invalid_cut.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

struct JointSet3 {
  double dip_deg = 0.0;            // degrees, in [0, 90]: 0 horizontal, 90 vertical
  double dip_direction_deg = 0.0;  // degrees, in [0, 360): the azimuth the plane dips towards,
                                   // clockwise from North (+y); 90 is East (+x)
  double spacing = 1.0;            // m, finite > 0: distance between neighbouring planes
  double offset = 0.0;             // m, finite: plane k is n . p = offset + k spacing
};

// Work bounds of cut_by_joint_sets, so absurd input fails fast instead of exhausting memory.
inline constexpr std::size_t max_cut_planes = 100'000;
inline constexpr std::size_t max_cut_pieces = 1'000'000;

// Throws InvalidCut naming "joint_sets[i].FIELD" and what was expected.
void check_joint_sets(std::span<const JointSet3> sets);

// The upward unit normal n of the set's planes (header).
Point3 joint_normal(const JointSet3& set);

// Plane k of the set: n . p = offset + k spacing, normal n (so "below" is the side n points away
// from).
Plane3 joint_plane(const JointSet3& set, std::int64_t k);

struct CutPiece3 {
  HalfspacePolyhedron piece;        // exact: its vertices are implicit three-plane points
  std::size_t part = 0;             // the region part it was cut from
  std::vector<std::int64_t> cell;   // per set, the k of the plane above it (it lies between
                                    // planes k - 1 and k)
};

// The pieces `sets` cut out of the region (convex parts, disjoint interiors). Throws InvalidCut.
template <NumberPolicy Policy>
std::vector<CutPiece3> cut_by_joint_sets(std::span<const ConvexPolyhedron> region,
                                         std::span<const JointSet3> sets);

struct CutBlock3 {
  std::vector<ConvexPolyhedron> parts;  // one for a convex block; named "<prefix>_<k>" (and
                                        // "<prefix>_<k>.<j>" for part j of a non-convex block)
};

// Options of cut_region.
struct CutOptions3 {
  // m³, finite >= 0. A block whose volume is below this is merged into the neighbouring block
  // with which it shares the largest face area, repeatedly, until every block reaches it or has
  // no neighbour (merge_small_blocks, header). 0: no merging.
  double min_block_volume = 0.0;
};

// The blocks for a scene, numbered from 1 (header). Throws InvalidCut (also for
// options.min_block_volume negative or not finite: the subject is "min_block_volume"), and
// InvalidCut naming "block near (x, y, z)" when a piece is too thin for its rounded vertices to
// make a valid polyhedron.
template <NumberPolicy Policy>
std::vector<CutBlock3> cut_region(std::span<const ConvexPolyhedron> region, std::span<const JointSet3> sets,
                                  const std::string& id_prefix, const CutOptions3& options = {});

// cut_region's merging alone (header), for a bound that depends on the unmerged blocks (a
// scene's "auto"): `blocks` as cut_region made them, those below options.min_block_volume
// merged, numbered from 1 again and their parts named after id_prefix as cut_region names them.
// Throws InvalidCut naming "min_block_volume" for a bound negative or not finite.
std::vector<CutBlock3> merge_small_blocks(std::vector<CutBlock3> blocks, const CutOptions3& options,
                                          const std::string& id_prefix);

}  // namespace rockcontact::kernel
