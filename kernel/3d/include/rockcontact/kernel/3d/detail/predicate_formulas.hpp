#pragma once
// The 3D predicate formula, written once and generic over the number type T, so the naive face
// (double), the interval stage and the exact stage (CGAL::Mpzf) evaluate the same expression.
// `Diff` builds a T from the difference of two input doubles; the formula reads the original
// input coordinates only.

#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::kernel::detail {

// ((p1 - p0) x (q1 - q0)) . (r1 - r0): the triple product of three difference vectors, degree 3.
// orient3d(a, b, c, d) is triple(a, b, a, c, a, d); the side of a point against a plane through
// an edge and parallel to another edge (an edge-edge separating axis) is triple(e0, e1, f0, f1,
// e0, x).
template <class T, class Diff>
T triple_formula(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                 const Point3& r0, const Point3& r1, Diff diff) {
  const T ux = diff(p1.x, p0.x), uy = diff(p1.y, p0.y), uz = diff(p1.z, p0.z);
  const T vx = diff(q1.x, q0.x), vy = diff(q1.y, q0.y), vz = diff(q1.z, q0.z);
  const T wx = diff(r1.x, r0.x), wy = diff(r1.y, r0.y), wz = diff(r1.z, r0.z);
  const T nx = T(uy * vz) - T(uz * vy);
  const T ny = T(uz * vx) - T(ux * vz);
  const T nz = T(ux * vy) - T(uy * vx);
  return T(T(nx * wx) + T(ny * wy)) + T(nz * wz);
}

}  // namespace rockcontact::kernel::detail
