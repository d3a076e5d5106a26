#pragma once
// The convex hull of points in the plane for tests: Andrew's monotone chain in double, strictly
// convex (collinear and repeated points dropped), counter-clockwise from the lowest x (then y);
// fewer than three distinct points come back as they are.
// The orientation test is the plain double formula: exact for points on a coarse binary grid
// (what the 2D potential tests use), and within its rounding elsewhere, which is all a test that
// compares an area with a tolerance needs.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::testing {

inline std::vector<kernel::Point2> convex_hull2(std::vector<kernel::Point2> points) {
  using kernel::Point2;
  std::sort(points.begin(), points.end(),
            [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto turn = [](const Point2& o, const Point2& a, const Point2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<Point2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 0 ? k - 1 : 0);
  return hull;
}

}  // namespace rockcontact::testing
