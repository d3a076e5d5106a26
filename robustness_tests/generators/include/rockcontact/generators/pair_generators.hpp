#pragma once
// Generators of nasty convex polygon pairs (cp, tp) for the robustness tests, the benchmarks and
// fuzz targets: every pair is valid input for ConvexPolygon::make (CCW, strictly convex, no
// repeated vertex), and the same (family, seed, index) gives the same pair on every platform.
//
// Validity is by construction: each polygon is the strict convex hull (convex_hull below) of
// a generated point set, computed with the kernel's exact orientation predicate, so a rounded
// coordinate can never leave a collinear or reflex vertex behind. The defining property of the
// exact families (a vertex on an edge, a shared vertex, collinear edges, a lattice touch) is
// checked with the same exact predicate; a violation is a generator bug (std::logic_error).
//
// Determinism: std::mt19937_64 (its output sequence is fixed by the C++ standard) with
// distributions written here, and no transcendental function: directions come from the
// rational parametrisation of the circle, ((1 - t^2), 2 t) / (1 + t^2), so only + - * / and
// sqrt (correctly rounded by IEEE 754) and ldexp, round and nextafter (exact) touch the
// numbers; angles are drawn as numbers and turned into tangents by a short series. Build
// with -ffp-contract=off (the rockcontact_options target does) so that no fused multiply-add
// changes a last bit.
//
// Families (lengths in metres, polygons about 1 m across):
//   random            3-10 vertices on random ellipses; tp at a random distance (overlap or
//                     separate), near contact (a tp corner placed at a cp corner, up to 0.2 m
//                     aside, then moved +-2 cm along the direction of approach), or sharing a
//                     cp vertex from outside (an exact touch).
//   short_edges       random polygons with every corner chamfered by a 0.01 m edge, placed near
//                     contact as above with a gap in [-2 cm, +0.5 cm].
//   wedge_5deg        triangles or blunt-backed quadrilaterals with a 5° (0.5°) apex angle,
//   wedge_0_5deg      tips poking into each other (mostly anti-parallel, some crossing).
//   near_parallel     a tp edge facing a cp edge at an angle of 2e-12 to 1e-6 rad (log-uniform,
//                     either sign), offset across the cp edge line by 0 or +-(1e-15 .. 2e-6).
//   vertex_on_edge    cp edge A->B with B - A = 2^-q (a, b), (a, b) an integer direction
//                     (half short: (1, 0), (2, 1), ..., q = 1..3; half long: a, b of 19-21
//                     bits, q = 20); the tp vertex V = A + k / 2^m (B - A), m <= 20, exactly on
//                     the edge. Variants: tp outside (touch), tp crossing the edge line at V,
//                     and V moved by 2^-j times the edge's normal 2^-q (-b, a), 24 <= j <=
//                     50 - q, inside (penetration) or outside (gap).
//   vertex_on_vertex  tp has a vertex of cp; tp outside one of that vertex's edge lines
//                     (touch) or turned into cp (overlap).
//   edge_on_edge      a tp edge on the line of a cp edge (directions as in vertex_on_edge),
//                     endpoints at k / 2^m along it; tp on the outside (touch along a segment
//                     or at a point, or separate) or on the inside (overlap sharing a boundary
//                     segment).
//                     These three families put every point on the grid 2^-50 m below 4 m in
//                     magnitude: the constructions above are exact sums, but the predicates'
//                     products need not be exact in double.
//   offset_1e6        a pair of one of the families above, snapped to the grid 2^-33 m and
//                     translated by (1e6, -1e6) m. The translation is exact: every coordinate
//                     is a multiple of 2^-33 and stays below 2^20 in magnitude, so each sum is a
//                     multiple of 2^-33 below 2^20 = 2^53 * 2^-33, a double (checked with an
//                     error-free sum). Snapping tilts near_parallel edges to at least ~1e-10
//                     rad or exactly parallel.
//   lattice_touch     vertices on the lattice (Z / 8)^2 within 1-2 m; half of the pairs put tp
//                     in the closed outer half-plane of a cp edge through a lattice point of
//                     that edge (an exact touch), half are two independent lattice polygons.
//   sliver            thin triangles, diamonds, hexagons and rectangles 0.5-1.5 m long with
//                     length / width log-uniform in [1e2, 1e6] (diameter / width within 1e-12
//                     of it), against another sliver or an ordinary polygon: crossing (both
//                     contain a common point, well inside), overlapping (a sliver's tip inside
//                     the other polygon; two slivers nearly aligned, within about the tip's own
//                     angle), touching (a sliver's tip at the other's vertex, or an ordinary
//                     polygon at a sliver's vertex, exactly, from outside an edge line) or
//                     separated by a gap of 1e-12 to 8e-3 m.
//   wedge_0_1deg      wedges as in wedge_5deg with an apex angle log-uniform in [0.1°, 1°]:
//                     tips poking into each other, or a tip poking into a long side (up to half
//                     the local width deep, or short of it) at 6° to 90° from it.
//   tiny_edges        random polygons (corners >= 29°, edges >= 0.05 of the diameter) with every
//                     corner cut by a chamfer edge of c times the diameter, c log-uniform in
//                     [1e-6, 1e-2]; tp placed corner to corner with cp at a gap of -2c .. c
//                     times the diameter, laterally 0 or within 3c.
//   near_parallel_ulp a tp edge P0 -> P1 facing a cp edge A -> B at an angle log-uniform in
//                     [1e-13, 1e-11] rad, turned away from cp or into it; P0 exactly on the
//                     line A -> B (cp snapped to 2^-30 m, P0 = A + j / 2^m (B - A)), or that
//                     point with one coordinate moved by one ulp (std::nextafter) to the inside
//                     or the outside of the line, the side checked with exact orientation.
//   nested            the inner polygon (tp or cp) strictly inside the outer one, or touching
//                     its boundary from inside: a vertex exactly on an outer edge, an edge
//                     along an outer edge, or a shared vertex.
//   identical         tp has exactly cp's vertices (from another start vertex), or all of them
//                     but one, moved by one ulp in one coordinate (still strictly convex).
//   offset_1e9        a pair of one of the non-meta families above, snapped to the grid
//                     2^(E - 53) m and translated by (+-X, +-Y), X and Y log-uniform in [1e6,
//                     1e9] m, where 2^E exceeds |offset| + |coordinates| + 1: every snapped
//                     coordinate, the offset and each sum are multiples of 2^(E - 53) below 2^E,
//                     so each has at most 53 significant bits and the translation is exact
//                     (checked). At 1e9 m the grid is 2^-23 m ~ 1.2e-7 m: the base's sub-grid
//                     features (1-ulp moves, the thinnest slivers, 1e-6 m chamfers) are rounded
//                     to grid size or away, as they would be in a model that far out.
//   rotated           a pair of a uniformly chosen non-meta family rotated as a whole by the
//                     rational rotation ((1 - t^2), 2 t) / (1 + t^2), t = k / 2^16 in [-1, 1],
//                     possibly plus a half turn, about a centre on the grid 2^-8 m within 1 m,
//                     each polygon re-hulled. The rotated coordinates are rounded: the base's
//                     exact incidences (vertex on edge, collinear edges, shared vertices, 1-ulp
//                     crossings) become near-incidences at the rounding level, which is the
//                     point: the same configurations in general position.
//   lattice_concurrent  points where three edge-distance lines meet exactly, on an IP edge
//                     (campaign seed 20261124, lattice_touch pair 394832): half the pairs are a
//                     right triangle whose sides are a Pythagorean triple times 2^-4 m (its
//                     incentre is a grid point where all three distance lines meet) with a tp
//                     edge through the incentre along a small integer direction; half are two
//                     overlapping lattice hulls as in lattice_touch (tp offset by up to 4 steps).
//   nested_rotated    nested polygons touching along an edge (3/4) or by an inner vertex on an
//                     outer edge (1/4), the inner one as cp or tp, then rotated as in `rotated`:
//                     an inner edge along an outer one to within rounding, whose near-parallel
//                     crossing is an inner vertex (seed 20261124, rotated pair 384916, swapped).
//                     The recipe names the rotation and the nesting.
//   The two meta families (offset_1e9, rotated) generate their base with generate_pair and a
//   seed drawn from their own stream, and the recipe names it ("base FAMILY seed S index 0: ..."),
//   so the base is regenerated from the recipe alone.
//
// Recipes: the family's parameters follow the prefix ("aspect", "angle_deg", "chamfer",
// "placement", "offset", "grid", "t", "centre", "base"), numbers printed with %g (correctly
// rounded, the same text on every platform); the rotation's t and centre are dyadic and printed
// exactly.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::robustness {

using kernel::Point2;
using kernel::Vector2;

enum class Family : std::uint8_t {
  random,
  short_edges,
  wedge_5deg,
  wedge_0_5deg,
  near_parallel,
  vertex_on_edge,
  vertex_on_vertex,
  edge_on_edge,
  offset_1e6,
  lattice_touch,
  sliver,
  wedge_0_1deg,
  tiny_edges,
  near_parallel_ulp,
  nested,
  identical,
  offset_1e9,
  rotated,
  lattice_concurrent,
  nested_rotated,
};

// New families are appended: a family's enumerator value seeds its stream, so the existing
// streams stay as they were.
inline constexpr std::array<Family, 20> all_families{
    Family::random,         Family::short_edges,    Family::wedge_5deg,       Family::wedge_0_5deg,
    Family::near_parallel,  Family::vertex_on_edge, Family::vertex_on_vertex, Family::edge_on_edge,
    Family::offset_1e6,     Family::lattice_touch,  Family::sliver,           Family::wedge_0_1deg,
    Family::tiny_edges,     Family::near_parallel_ulp, Family::nested,        Family::identical,
    Family::offset_1e9,     Family::rotated,        Family::lattice_concurrent, Family::nested_rotated};

std::string_view to_string(Family family);
std::optional<Family> parse_family(std::string_view name);

struct PolygonPair {
  std::vector<Point2> cp;  // contact polygon, CCW, strictly convex (m)
  std::vector<Point2> tp;  // target polygon, CCW, strictly convex (m)
  // How the pair was made: "FAMILY seed S index I" and the family's parameters, enough to
  // tell a reader what the case is and to regenerate it.
  std::string recipe;
};

// The pair number `index` of `family` in the stream of `seed`. Pairs are independent of each
// other: a failing pair is reproduced from its three numbers alone.
PolygonPair generate_pair(Family family, std::uint64_t seed, std::uint64_t index);

// The strict convex hull of `points`, CCW from the lowest-leftmost vertex, decided with exact
// orientation: no repeated and no collinear vertex. Fewer than 3 vertices when the points are
// all collinear (or fewer than 3 distinct).
std::vector<Point2> convex_hull(std::vector<Point2> points);

// Every coordinate rounded to the nearest multiple of 2^grid_exponent, each polygon replaced
// by its strict convex hull; nullopt when a polygon collapses below 3 vertices.
std::optional<PolygonPair> snap_to_grid(const PolygonPair& pair, int grid_exponent);

// The pair translated by `offset` when every coordinate sum is exact, else nullopt.
std::optional<PolygonPair> translate_exactly(const PolygonPair& pair, Vector2 offset);

}  // namespace rockcontact::robustness
