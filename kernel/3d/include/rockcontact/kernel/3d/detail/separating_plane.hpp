#pragma once
// The candidate separating planes of two convex polyhedra (overlap.hpp states the method): a
// face plane of one block against the vertices of the other, or the plane through an edge of A
// parallel to an edge of B. Shared by the overlap verdict and the contact set, which needs the
// zero-gap plane itself. Every decision is an exact sign under the staged policies.

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel::detail {

// What a candidate plane says about the pair.
enum class Gap { none, zero, positive };  // not a separating plane / weakly / strictly

// The plane of a face of `p` against the vertices of `q`.
template <NumberPolicy Policy>
Gap face_gap(const ConvexPolyhedron& p, const ConvexPolyhedron::Face& face, const ConvexPolyhedron& q) {
  const Point3 &f0 = p[face[0]], &f1 = p[face[1]], &f2 = p[face[2]];
  Gap gap = Gap::positive;
  for (const Point3& x : q.vertices()) {
    const Sign s = orient3d<Policy>(f0, f1, f2, x);
    if (s == Sign::negative) return Gap::none;
    if (s == Sign::zero) gap = Gap::zero;
  }
  return gap;
}

// The common sign of triple(e, f, origin -> x) over the vertices x of `p`, or zero when the
// plane through origin with normal e x f cuts p (both signs occur). Never all zero: p is solid.
template <NumberPolicy Policy>
Sign side(const Point3& e0, const Point3& e1, const Point3& f0, const Point3& f1, const Point3& origin,
          const ConvexPolyhedron& p) {
  Sign side = Sign::zero;
  for (const Point3& x : p.vertices()) {
    const Sign s = triple_sign<Policy>(e0, e1, f0, f1, origin, x);
    if (s == Sign::zero) continue;
    if (side == Sign::zero) {
      side = s;
    } else if (s != side) {
      return Sign::zero;
    }
  }
  return side;
}

// The plane through edge ea of `a` parallel to edge eb of `b` (normal e x f), when it and its
// parallel through eb support a and b on opposite sides: the sign of the gap between them.
template <NumberPolicy Policy>
Gap edge_gap(const ConvexPolyhedron& a, const ConvexPolyhedron::Edge& ea, const ConvexPolyhedron& b,
             const ConvexPolyhedron::Edge& eb) {
  const Point3 &e0 = a[ea.first], &e1 = a[ea.second], &f0 = b[eb.first], &f1 = b[eb.second];
  if (parallel<Policy>(e0, e1, f0, f1)) return Gap::none;
  const Sign side_a = side<Policy>(e0, e1, f0, f1, e0, a);
  if (side_a == Sign::zero) return Gap::none;
  const Sign side_b = side<Policy>(e0, e1, f0, f1, f0, b);
  if (side_b != -side_a) return Gap::none;
  const Sign gap = side_b * triple_sign<Policy>(e0, e1, f0, f1, e0, f0);
  if (gap == Sign::negative) return Gap::none;
  return gap == Sign::zero ? Gap::zero : Gap::positive;
}

}  // namespace rockcontact::kernel::detail
