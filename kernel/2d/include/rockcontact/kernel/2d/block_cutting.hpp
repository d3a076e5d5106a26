#pragma once
// Block cutting in 2D: the blocks that joint sets cut out of a region, and the exact convex
// partition of a simple polygon (DESIGN.md, "Block cutting").
//
// cut_region, step by step (CGAL 2D arrangements on the exact-constructions kernel; each input
// double is the exact rational it denotes):
//   1. Validate the region (>= 3 finite vertices, simple, counter-clockwise: exact tests),
//      every joint set and the options (each message names the field), and bound the work:
//      at most max_cut_trace_lines lines and max_cut_trace_pieces segments in all, at most
//      max_cut_trace_crossings potential crossings.
//   2. Insert the region boundary into an empty arrangement; its one bounded face is flagged
//      `inside`. An observer copies the flag to the new face whenever a face is split, so every
//      face carved out of the region later is inside and every other face is not.
//   3. Generate the traces of each set: trace k lies on the line n . p = offset + k spacing,
//      n = (-sin dip, cos dip); a persistent trace is the line clipped, in double, to a disc
//      around the region's bounding box (6 % larger than the box's circumscribed circle); a
//      non-persistent one is cut into pieces [j (L + g), j (L + g) + L] of the coordinate s
//      along t = (cos dip, sin dip) from the foot point (offset + k spacing) n. End points are
//      computed in double (multiples of 90 degrees use exact unit vectors, so axis-parallel
//      traces lie exactly on their lines) and then taken as exact. All segments go into the
//      arrangement in one sweep; crossings, overlaps and T-junctions are computed exactly.
//   4. Remove the dead-end traces of inside faces: the edges with the same face on both sides
//      (bridges of the face's boundary graph). Removing a bridge never changes which other
//      edges are bridges, so one pass removes whole dead-end trees (chains of antennas); a
//      non-persistent trace that separates no two blocks leaves nothing behind, as in
//      block-cutting codes.
//   5. Merge small blocks (only when options.min_block_area > 0). The area of every inside face
//      is computed exactly (shoelace sum over its boundary cycles in the kernel's lazy exact
//      numbers: interval arithmetic, with GMP rationals only where the intervals cannot decide),
//      so which faces are fragments and the order they are processed in never depend on
//      rounding. Fragments (area < min_block_area) are processed smallest area first, ties by
//      their vertex sequence from the lowest, then leftmost vertex (exact comparisons). A
//      fragment's neighbours are the inside faces across an edge of its outer boundary (faces
//      that only share a vertex are not neighbours). A neighbour that meets the fragment in
//      more than one place (two separate chains of shared edges, or a chain and a lone vertex)
//      is passed over: the union of two such faces always surrounds the faces between the places
//      where they meet, so removing all the shared edges would leave a hole, and removing only
//      the longest chain would leave the others as a slit traversed twice (not a simple polygon
//      either). Every other neighbour shares one contiguous chain of edges (or the fragment's
//      whole outer boundary, when the fragment fills a hole of the neighbour); its length is
//      summed in double from the exactly rounded edge vectors, the longest wins, ties to the
//      neighbour whose vertex sequence comes first. The chain's edges and the vertices inside
//      it are removed (a filled hole disappears), the two faces become one, of the summed exact
//      area, and it is processed again while still below the bound. A fragment with no neighbour it can
//      merge with stays as it is, and is tried again whenever one of its neighbours grows by a
//      merge. Merged blocks are usually non-convex, as intended (the engine splits non-convex
//      blocks into convex parts).
//   6. Each inside face is a block: its outer boundary, counter-clockwise, with the vertices
//      collinear with their neighbours dropped (exact orientation, before rounding: a trace
//      ending on another trace, a trace meeting an edge collinearly, a region vertex on a
//      straight boundary, the end of an edge removed by step 5). Coordinates are then rounded
//      to the nearest double.
//
// Guarantees, or InvalidCut: every block is counter-clockwise and simple, with no repeated and
// no collinear vertex, decided exactly on the rounded doubles; blocks tile the region (up to the
// rounding of their vertices, <= half an ulp per coordinate; vertices shared by neighbouring
// blocks round identically). InvalidCut is thrown, with the block's approximate location, for
// a block that is not a simple polygon (a closed loop of traces strictly inside it, i.e. a face
// with a hole; or a boundary touching itself at a vertex) and for a block whose rounded vertices
// are no longer a valid polygon (a sliver thinner than the rounding). Blocks are ordered by
// their lowest, then leftmost vertex, which comes first in the block, ties broken by the
// following vertices: the output depends only on the input values. With min_block_area > 0,
// every block's exact area is >= min_block_area unless the block has no neighbour it can merge
// with (e.g. the whole region is one small block); the area polygon_area reports on the
// rounded output can differ from the exact one by the rounding (about half an ulp of the
// coordinates times the perimeter), so a block within that of the bound may report slightly
// less. A merge removes only the shared edges and the vertices inside their chain (which no
// third block has), so the blocks still tile the region.
//
// convex_partition: CGAL::optimal_convex_partition_2 (Greene's dynamic programme, O(n^4);
// fewest parts, the polygon's own vertices only, no Steiner points) on the exact kernel, after
// dropping collinear vertices exactly; every part is strictly convex and counter-clockwise. All
// output coordinates are input doubles, so nothing is rounded.

#include <cstddef>
#include <span>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/invalid_cut.hpp"

namespace rockcontact::kernel {

// One joint set: parallel traces at a constant perpendicular spacing.
struct JointSet {
  double dip_deg = 0.0;       // degrees, in [0, 180): angle of the traces from +x, counter-clockwise
  double spacing = 1.0;       // m, finite > 0: perpendicular distance between neighbouring traces
  double offset = 0.0;        // m, finite: trace k lies on n . p = offset + k spacing,
                              // n = (-sin dip, cos dip)
  double trace_length = 0.0;  // m, finite >= 0: 0 means persistent (infinite) traces; > 0: each
  double gap = 0.0;           // line carries traces of this length separated by gaps of `gap`
                              // (m, finite >= 0, only with trace_length > 0): with s the
                              // coordinate along t = (cos dip, sin dip) from the foot point
                              // (offset + k spacing) n, the traces are [j (L + g), j (L + g) + L]
                              // for every integer j
};

// Bad input to cut_region or convex_partition is an InvalidCut (core/invalid_cut.hpp), its
// subject "region" or "polygon" (the outline), "joint_sets[1].spacing", "min_block_area" or
// "block near (2.5, 7.5)".

// Work bounds of cut_region (step 1), so absurd input fails fast instead of exhausting memory.
// Lines: trace lines of all sets that can meet the region (those within its extent along each
// set's normal, plus one on each side). Pieces: segments inserted (one per persistent line; one
// per trace of a non-persistent set near the region). Crossings: the sum
// over pairs of non-parallel sets of the product of their line counts, an upper bound on the
// arrangement's trace-trace vertices (an arrangement costs roughly 0.5 kB per vertex).
inline constexpr std::size_t max_cut_trace_lines = 1'000'000;
inline constexpr std::size_t max_cut_trace_pieces = 1'000'000;
inline constexpr double max_cut_trace_crossings = 1e7;

// Options of cut_region.
struct CutOptions {
  // m², finite >= 0. A block whose area is below this is merged into the neighbouring block
  // (inside the region) with which it shares the longest boundary, repeatedly, until every
  // block reaches it or has no neighbour left to merge with (step 5). 0: no merging.
  double min_block_area = 0.0;
};

// The blocks that `sets` cut out of `region` (a simple counter-clockwise polygon, convex or
// not), each counter-clockwise, in the order described above. With no sets, the region itself
// (collinear vertices dropped). Throws InvalidCut (also for options.min_block_area negative or
// not finite: the message names "min_block_area").
std::vector<std::vector<Point2>> cut_region(std::span<const Point2> region,
                                            std::span<const JointSet> sets,
                                            const CutOptions& options = {});

// The fewest strictly convex counter-clockwise parts of a simple counter-clockwise polygon,
// whose vertices are the polygon's own; a convex polygon comes back as one part with its
// collinear vertices dropped. Parts are ordered like cut_region's blocks. Throws InvalidCut for a
// polygon that is too small, not finite, not simple or clockwise (messages name "polygon").
std::vector<std::vector<Point2>> convex_partition(std::span<const Point2> polygon);

// Signed area of a simple polygon, m² (positive when counter-clockwise): the shoelace formula
// in double on coordinates taken relative to the first vertex, so a polygon far from the origin
// loses no more than one near it. 0 for fewer than 3 vertices.
double polygon_area(std::span<const Point2> polygon);

}  // namespace rockcontact::kernel
