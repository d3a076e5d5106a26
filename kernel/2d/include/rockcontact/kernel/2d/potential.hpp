#pragma once
// The shortest-exit distance potential of a convex polygon (seed 000 §3.2.2, eq. 12-14).
//
//   d_exit(p) = min over edges k of the distance from p to the line of edge k   (p inside)
//   phi(p)    = kn * d_exit(p) / H                                                (Pa)
//
// For a convex polygon the distance to the boundary is the distance to the nearest edge line,
// and it is a concave, piecewise-linear function of p whose kinks lie on the medial axis.
// Outside the polygon the potential is not defined; exit_distance returns the smallest signed
// distance, which is negative there.

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

// Signed distance (m) from p to the boundary of `polygon`: > 0 inside, 0 on the boundary,
// < 0 outside (then it is minus the distance to the farthest violated edge line, not the true
// Euclidean distance to the polygon). Evaluated in double.
double exit_distance(const ConvexPolygon& polygon, const Point2& p);

// phi(p) = kn d_exit(p) / H (seed 000 eq. 14): kn in Pa, H in m, result in Pa.
inline double potential(const ConvexPolygon& polygon, const Point2& p, double kn, double H) {
  return kn * exit_distance(polygon, p) / H;
}

}  // namespace rockcontact::kernel
