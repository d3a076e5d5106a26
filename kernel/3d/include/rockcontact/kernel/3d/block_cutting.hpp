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
// given as its convex parts; the blocks are ordered by their first piece.
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

// The blocks for a scene, numbered from 1 (header). Throws InvalidCut, and InvalidCut naming
// "block near (x, y, z)" when a piece is too thin for its rounded vertices to make a valid
// polyhedron.
template <NumberPolicy Policy>
std::vector<CutBlock3> cut_region(std::span<const ConvexPolyhedron> region, std::span<const JointSet3> sets,
                                  const std::string& id_prefix);

}  // namespace rockcontact::kernel
