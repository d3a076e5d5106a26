#pragma once
// FT-generic constructions shared by the kernel and the contact layer. FT is double (Float,
// Filtered, Checked) or ExactRational (Exact, exact_number.hpp); with ExactRational every
// operation here is exact except NumberOps::sqrt. Nothing here decides anything: callers have
// already fixed the combinatorics with exact predicates.

#include <span>
#include <type_traits>
#include <vector>

#include "rockcontact/kernel/core/detail/number_ops.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel::detail {

template <class FT>
struct PointT {
  FT x;
  FT y;
};

template <class FT>
PointT<FT> lift(const Point2& p) {
  return {NumberOps<FT>::from(p.x), NumberOps<FT>::from(p.y)};
}

template <class FT>
Point2 round(const PointT<FT>& p) {
  return {NumberOps<FT>::to_double(p.x), NumberOps<FT>::to_double(p.y)};
}

template <class FT>
FT cross(const FT& ux, const FT& uy, const FT& vx, const FT& vy) {
  return ux * vy - uy * vx;
}

// The crossing of line (p, q) with segment (t0, t1): t0 + s (t1 - t0), s from the line's
// implicit equation; the plain formula (crossing_point.hpp filters it for the Filtered policy).
// In double s is clamped to [0, 1], which keeps the point on the segment (the combinatorics
// already say it is there); the error of each coordinate is then a few ulps of |X| plus
// |t1 - t0| times the error of s, which grows as the two lines approach parallel (1 / sin of
// their angle). When both cross products round to zero (lines parallel to within rounding) s
// is 0 / 0: NaN fails every comparison, so the clamp is written to send it to 0, the segment's
// start, as good as any point of it. In ExactRational the point is exact.
template <class FT>
PointT<FT> construct_crossing(const Point2& p, const Point2& q, const Point2& t0, const Point2& t1) {
  using Ops = NumberOps<FT>;
  const FT lx = Ops::from(q.x) - Ops::from(p.x), ly = Ops::from(q.y) - Ops::from(p.y);
  const FT dx = Ops::from(t1.x) - Ops::from(t0.x), dy = Ops::from(t1.y) - Ops::from(t0.y);
  const FT wx = Ops::from(p.x) - Ops::from(t0.x), wy = Ops::from(p.y) - Ops::from(t0.y);
  FT s = cross(lx, ly, wx, wy) / cross(lx, ly, dx, dy);
  if constexpr (std::is_same_v<FT, double>) s = s >= 0.0 ? (s > 1.0 ? 1.0 : s) : 0.0;
  return {Ops::from(t0.x) + s * dx, Ops::from(t0.y) + s * dy};
}

// Area and area centroid of a polygon (shoelace, in a frame centred on its first vertex so
// that a polygon far from the origin loses no digits).
template <class FT>
struct AreaCentroid {
  FT area;
  PointT<FT> centroid;
};

template <class FT>
AreaCentroid<FT> area_centroid(std::span<const PointT<FT>> v) {
  FT twice_area(0), cx(0), cy(0);
  const PointT<FT>& o = v[0];
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const FT ax = v[i].x - o.x, ay = v[i].y - o.y;
    const FT bx = v[i + 1].x - o.x, by = v[i + 1].y - o.y;
    const FT w = cross(ax, ay, bx, by);
    twice_area += w;
    cx += w * (ax + bx);
    cy += w * (ay + by);
  }
  const FT area = twice_area / FT(2);
  if (twice_area == FT(0)) {
    // A sliver whose constructed vertices are collinear (in double: an exact overlap thinner
    // than the rounding of its vertices) has no centroid; the mean of its vertices is a point
    // on it, which is all a moment reference needs.
    FT sx(0), sy(0);
    for (const PointT<FT>& p : v) {
      sx += p.x - o.x;
      sy += p.y - o.y;
    }
    const FT n(static_cast<int>(v.size()));
    return {area, {o.x + sx / n, o.y + sy / n}};
  }
  return {area, {o.x + cx / (FT(3) * twice_area), o.y + cy / (FT(3) * twice_area)}};
}

}  // namespace rockcontact::kernel::detail
