#pragma once
// The distance of two separate convex polyhedra and a pair of closest points.
//
// Whether the pair is separate is decided exactly by classify_overlap (overlap.hpp) under
// Filtered, Exact and Checked; the result is nullopt unless it is.
//
// Method: the minimum over feature pairs. Two disjoint convex polyhedra attain their distance
// at a pair of points on their boundaries, and some pair of features containing them (vertex,
// edge or face of each) has its own closest points there; a face-face, face-edge or edge-face
// closest pair can always be slid to a vertex-face, face-vertex or edge-edge one, and a
// parallel edge-edge pair to a vertex-edge one. So the distance is the minimum of
//   * vertex x of one block against a face of the other whose plane's foot of x lies in the
//     face (|(x - f0) . n| / |n|, n the face's normal; the projection of seed 001 §2.1 eq. 1);
//   * vertex against edge, the foot clamped to the edge (this covers vertex-vertex);
//   * edge against edge, not parallel, where both lines' closest points fall inside the edges
//     (the common perpendicular of seed 001 §2.1 eqs. 2-3).
// Every candidate is the distance between a point of A and a point of B, so none is below the
// true distance, and the true closest pair is among them: the minimum is exact in exact
// arithmetic, and each comparison and clamp is a comparison of rationals under Exact.
//
// Constructions: under Float and Filtered in double in a local frame (the pair translated by a
// vertex of A); under Exact in exact rationals, the distance as the square root of the exact
// squared distance (MPFR, 2^-255 relative) and every coordinate rounded once.
//
// Accuracy under Filtered (u = 2^-53, S the largest local coordinate of the pair): the local
// coordinates are within u S of the input. A foot on a face plane, x - ((x - f0).n / n.n) n,
// is within about 12 u S of the exact foot (the scalar's absolute error is 5 u |x - f0| |n| /
// |n|^2, times n); a foot clamped to an edge, p + t e, within about 10 u S. An edge-edge
// candidate's parameters lose accuracy as the edges approach parallel (by 1/sin^2 of their
// angle), but the points stay on their edges, so the candidate remains an upper bound, and
// for the minimising pair the value grows by at most the slide across the common
// perpendicular. Each value is the length of the difference of the two points, not a
// difference of squares, so it does not cancel at small distances. The reported distance is
// within about 25 u S of the exact one (plus that slide for a near-parallel closest edge
// pair); the closest points lie within about 12 u S of the blocks and are rounded once more
// into global coordinates. Measured on the contact3d reference: |distance - exact| <=
// 6.4e-17 S (tests/distance_test.cpp prints it); the tests assert 1e-9 relative or 1e-12 S.

#include <optional>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

struct Separation {
  double distance;  // metres, > 0
  Point3 point_a;   // a closest point on a's boundary
  Point3 point_b;   // a closest point on b's boundary, |point_b - point_a| = distance
};

template <NumberPolicy Policy>
std::optional<Separation> separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

}  // namespace rockcontact::kernel
