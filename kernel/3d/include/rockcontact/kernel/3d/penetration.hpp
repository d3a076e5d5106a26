#pragma once
// The penetration of two overlapping convex polyhedra: the minimum translation distance and its
// direction.
//
// Whether the pair overlaps (interiors meet) is decided exactly by classify_overlap
// (overlap.hpp) under Filtered, Exact and Checked; the result is nullopt unless it does.
//
// Method. Translating tp by d makes it meet cp exactly when d lies in the Minkowski difference
// M = cp - tp = {a - b}, and overlap when d lies in M's interior; the pair overlaps, so the
// origin is inside M, and the minimum translation distance is the distance from the origin to
// M's boundary, attained on the plane of some facet of M. For any direction n (unnormalised),
// the support extent
//   h(n) = max over vertices a of cp of a.n - min over vertices b of tp of b.n
// is M's support function: the half-space {x.n <= h(n)} contains M, so translating tp by
// (h(n)/|n|) along n/|n| makes the pair touch or come apart, and h(n)/|n| >= the minimum; for
// the normal of the facet nearest to the origin it is the minimum. M's facet normals are among
// the outward face normals of cp, the inward face normals of tp and +-(e x f) for a
// non-parallel edge e of cp and edge f of tp (overlap.hpp), so the minimum of h(n)/|n| over
// these candidates is the depth and its n the direction (pointing from cp towards tp). This is
// the shortest exit of seed 001 §2.2.1 (eq. 4: among candidate contact planes, the one with the
// shortest normal penetration) taken over every candidate plane of the pair rather than those
// next to one contacting vertex or edge.
// The candidates are unnormalised, so they are compared by h |h| / |n|^2, which keeps the
// sign (h > 0 for every candidate of an overlapping pair in exact arithmetic: no candidate
// plane separates it even weakly) and needs no square root.
//
// Constructions: under Exact in exact rationals, the comparison of the squared values exact,
// depth = sqrt(h^2/|n|^2) and normal = n / sqrt(|n|^2) in MPFR (2^-255 relative) and rounded
// once. Under Float and Filtered in double in a local frame (translated by a vertex of cp;
// u = 2^-53, S the largest local coordinate): each candidate's value is the support extent of
// the direction n actually formed, within a few u S, so every value still bounds the depth
// from above up to that; the minimiser's n is off the exact facet normal by an angle of a few
// u (u / sin a for an edge pair at angle a), which moves its value by at most that angle
// times S. So the depth is within about (8 + 1/sin a) u S of the exact one, and among
// candidates tied within that the choice may differ from the exact one: any direction whose
// h/|n| is within 1e-9 relative of the minimum is an acceptable answer (the contact3d
// reference lists them as `normals_near`). Measured on the contact3d reference:
// |depth - exact| <= 2.2e-16 S, every normal within 1e-6 rad of a near-minimal direction
// (tests/penetration_test.cpp).

#include <optional>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

struct Penetration {
  double depth;   // metres, > 0: the minimum translation distance
  Point3 normal;  // unit vector from cp towards tp: tp moved by depth * normal touches cp
};

template <NumberPolicy Policy>
std::optional<Penetration> penetration(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp);

}  // namespace rockcontact::kernel
