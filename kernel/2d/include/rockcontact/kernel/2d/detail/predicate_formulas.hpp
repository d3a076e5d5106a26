#pragma once
// The predicate formulas, written once and generic over the number type T, so the naive face
// (double), the interval stage and the exact stage (CGAL::Mpzf) evaluate the same expression
// and cannot drift apart. `Diff` builds a T from the difference of two input
// doubles; every formula reads the *original* input coordinates, never a rounded derived point.

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel::detail {

// A line through two input points, oriented from p to q.
struct Line {
  Point2 p;
  Point2 q;
};

// (p1 - p0) x (q1 - q0): the cross product of two difference vectors, degree 2.
template <class T, class Diff>
T cross_formula(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1, Diff diff) {
  const T ux = diff(p1.x, p0.x);
  const T uy = diff(p1.y, p0.y);
  const T vx = diff(q1.x, q0.x);
  const T vy = diff(q1.y, q0.y);
  return T(ux * vy) - T(uy * vx);
}

// Side of the crossing X of lines a and b with respect to line c, times sign(D).
//
// With d1 = a.q - a.p, d2 = b.q - b.p, d3 = c.q - c.p, the crossing is X = a.p + (N/D) d1 where
//   D = d1 x d2,  N = (b.p - a.p) x d2.
// Its side of c is the sign of d3 x (X - c.p) = A + (N/D) B with A = d3 x (a.p - c.p) and
// B = d3 x d1, i.e. sign(D A + N B) * sign(D). This returns D A + N B (degree 4); the caller
// multiplies by sign(D), decided by the cross predicate. D != 0 is a precondition.
template <class T, class Diff>
T crossing_side_formula(const Line& a, const Line& b, const Line& c, Diff diff) {
  const T d1x = diff(a.q.x, a.p.x), d1y = diff(a.q.y, a.p.y);
  const T d2x = diff(b.q.x, b.p.x), d2y = diff(b.q.y, b.p.y);
  const T d3x = diff(c.q.x, c.p.x), d3y = diff(c.q.y, c.p.y);
  const T wx = diff(b.p.x, a.p.x), wy = diff(b.p.y, a.p.y);
  const T rx = diff(a.p.x, c.p.x), ry = diff(a.p.y, c.p.y);
  const T D = T(d1x * d2y) - T(d1y * d2x);
  const T N = T(wx * d2y) - T(wy * d2x);
  const T A = T(d3x * ry) - T(d3y * rx);
  const T B = T(d3x * d1y) - T(d3y * d1x);
  return T(D * A) + T(N * B);
}

}  // namespace rockcontact::kernel::detail
