#pragma once
// Generators of nasty convex polyhedron pairs (a, b) for the 3D robustness campaign, the 3D
// benchmark and the 3D fuzz target: the 3D counterpart of pair_generators.hpp. Every pair is
// valid input for ConvexPolyhedron::make, and the same (family, seed, index) gives the same
// pair on every platform (std::mt19937_64 with distributions written out, no transcendental
// function; see pair_generators.hpp on determinism).
//
// Validity is by construction: each block is the convex hull (convex_hull3 below) of a
// generated point set, computed by CGAL::convex_hull_3 with exact predicates on the doubles as
// given, its coplanar triangles merged into polygon faces and any vertex that is not a corner
// of the hull dropped, so every face is exactly planar and strictly convex.
//
// Exact families: the touching configurations are built on dyadic grids so that the contact
// is exact in double: the contact plane is z = 0, one block lies in z <= 0 with the touching
// feature (a face, an edge, a vertex) in z = 0, the other in z >= 0; moved by +-2^-j m (j in
// [20, 50]) along z they separate or overlap, which is exact too (every coordinate is a
// multiple of 2^-50 below 2 m in magnitude, so each sum has at most 53 significant bits). Each
// pair carries the verdict its construction implies (`expected`), or nullopt where it does not
// imply one (random placement, rounded rotations and deformations).
//
// Families (lengths in metres, blocks about 1 m across; "touch / gap / push" means the
// touching construction, or it moved apart by 2^-j, or into each other by 2^-j):
//   random            two hulls of 8-20 points in random ellipsoids, the second at a random
//                     offset of 0-1.6 m in a random direction.
//   face_face         coplanar faces touching: a's top face in z = 0 and b's bottom face in
//                     z = 0, both containing the origin strictly inside (partial face overlap);
//                     or b built on a copy of some vertices of a face of a random hull a (its
//                     face a subset of a's face, in a general plane). touch / gap / push for the
//                     first, touch for the second.
//   edge_edge         a's top edge on the x axis, b's bottom edge through the origin along a
//                     small integer direction (x, y, 0), crossing a's. touch / gap / push.
//   vertex_face       b's lowest vertex at a dyadic point strictly inside a's top face.
//                     touch / gap / push.
//   vertex_edge       b's lowest vertex at k/2^m along a's top edge. touch / gap / push.
//   near_parallel_5deg, near_parallel_0_5deg   b's bottom face tilted by about 5° (0.5°) from
//                     a's top face (slope a dyadic rounding of tan θ: exactly planar), b's
//                     lowest vertex inside a's top face. touch / gap / push.
//   sliver            a thin slab (prism of thickness 10^-6 to 10^-2 m) with b's vertex on its
//                     top face (touch / gap / push, pushed less than half the thickness), or
//                     a needle (1 m long, 10^-6 to 10^-2 m thick) at a random offset through
//                     a random hull.
//   short_edges       a cuboid with every corner cut by 0.01 m chamfers (edges of 0.01 m on a
//                     ~1 m block), b its mirror image across a's +x face, moved sideways
//                     by less than a quarter of that face: face-to-face among the tiny edges.
//                     touch / gap / push.
//   offset_1e6        a pair of a non-meta family snapped to the grid 2^-32 m and translated by
//                     (1e6, -1e6, 1e6) m, exact (multiples of 2^-32 below 2^21); the expected
//                     verdict is kept when the snap changed no coordinate.
//   rotated           a pair of a non-meta family turned by a rational rotation (from an integer
//                     quaternion), rounded and re-hulled: the exact incidences become
//                     near-incidences at the rounding level. No expected verdict.
//   deformed          two cuboids face to face (gap -10^-3 .. 10^-3 m), each deformed by a
//                     strain of up to 10^-3 and vertex jitter of 10^-12 to 10^-6 m and re-hulled:
//                     faces that were planar become nearly coplanar triangles. No expected
//                     verdict.
//   The meta families (offset_1e6, rotated) draw their base family and seed from their own
//   stream and name them in the recipe.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/overlap.hpp"

namespace rockcontact::robustness {

enum class Family3d : std::uint8_t {
  random,
  face_face,
  edge_edge,
  vertex_face,
  vertex_edge,
  near_parallel_5deg,
  near_parallel_0_5deg,
  sliver,
  short_edges,
  offset_1e6,
  rotated,
  deformed,
};

// New families are appended: a family's enumerator value seeds its stream.
inline constexpr std::array<Family3d, 12> all_families3d{
    Family3d::random,      Family3d::face_face,          Family3d::edge_edge,
    Family3d::vertex_face, Family3d::vertex_edge,        Family3d::near_parallel_5deg,
    Family3d::near_parallel_0_5deg, Family3d::sliver,    Family3d::short_edges,
    Family3d::offset_1e6,  Family3d::rotated,            Family3d::deformed};

std::string_view to_string(Family3d family);
std::optional<Family3d> parse_family3d(std::string_view name);

struct PolyhedronPair {
  kernel::ConvexPolyhedron a;
  kernel::ConvexPolyhedron b;
  Family3d family = Family3d::random;
  // The verdict the construction implies, nullopt where it implies none.
  std::optional<kernel::Overlap> expected;
  // "FAMILY seed S index I: parameters", enough to tell what the case is and to regenerate it.
  std::string recipe;
};

// The pair number `index` of `family` in the stream of `seed`; pairs are independent, so a
// failing pair is reproduced from its three numbers alone.
PolyhedronPair generate_pair3d(Family3d family, std::uint64_t seed, std::uint64_t index);

// The convex hull of `points` (finite doubles, taken exactly) as a validated polyhedron named
// `name`: coplanar hull triangles merged into one face, points that are not corners of the
// hull dropped. nullopt when the points are coplanar (no solid hull).
std::optional<kernel::ConvexPolyhedron> convex_hull3(std::string name, std::span<const kernel::Point3> points);

}  // namespace rockcontact::robustness
