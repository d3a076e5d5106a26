#pragma once
// The entrance block and the overlap verdict of two convex polygons (seed 000 §3.1.2, eq. 9,
// Tables 1-2).
//
//   E(A, B) = B - A + a0 = { b - a + a0 : a in A, b in B },  a0 = mean of A's vertices (any interior point of A serves).
//
// A and B overlap exactly when a0 lies in E(A, B): inside = interiors intersect (overlap), on
// the boundary = boundaries touch, outside = separate.
//
// Steps (O(n + m)):
//   1. start at B's lowest-leftmost vertex and -A's lowest-leftmost vertex (A's highest-rightmost);
//   2. merge the edge sequences of B and of -A by polar angle (both already sorted, CCW); equal
//      directions are merged into one edge, so E comes out strictly convex;
//   3. locate a0 against every edge of E.
// Step 3 never forms a0 or a vertex of E: a vertex of E is e = b_j - a_i + a0, so the side of a0
// with respect to the edge from e along direction v is sign(v x (a0 - e)) = sign(v x (a_i - b_j)),
// with v an edge of B or a reversed edge of A: a cross product of two differences of input
// points, decided exactly by cross_sign. a0 cancels; the verdict does not depend on it.
//
// Departure from the paper: Table 1 prunes invalid vertex-edge entrance candidates; the
// angle merge never generates them, which is the same result in linear time.

#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/overlap.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

// The verdict alone: no construction, no allocation, exact under Filtered and Exact.
template <NumberPolicy Policy>
Overlap classify_overlap(const ConvexPolygon& a, const ConvexPolygon& b);

struct EntranceBlock {
  std::vector<Point2> vertices;  // E(A,B), CCW, strictly convex; coordinates rounded once (m)
  Point2 reference;              // a0, the mean of A's vertices (m), rounded once
  Overlap status = Overlap::separate;
  // Distance from a0 to the boundary of E (m), >= 0: for `separate` the gap A must travel to
  // touch B; for `overlap` the minimum translation distance that separates them; 0 for `touch`.
  double distance = 0.0;
};

template <NumberPolicy Policy>
EntranceBlock compute_entrance_block(const ConvexPolygon& a, const ConvexPolygon& b);

// The penetration depth of A and B (m): when they overlap, the minimum translation distance
// that separates them (compute_entrance_block's `distance`), else 0. Each edge's distance is
// taken as the merge produces it, so E is never stored: no allocation under Float and
// Filtered. Under Exact the distance is exact up to its one square root, and equals
// compute_entrance_block<Exact>'s.
template <NumberPolicy Policy>
double compute_penetration_depth(const ConvexPolygon& a, const ConvexPolygon& b);

}  // namespace rockcontact::kernel
