#pragma once
// Convex polygons of a plane, as the 3D kernel's constructions meet them: the contact
// constraints' support corners (contact_constraints.cpp) and the face area two cut blocks share
// (block_cutting.cpp). Private to kernel/3d/src.

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace rockcontact::kernel::detail {

using Point2d = std::array<double, 2>;

// The convex polygon `subject` clipped by the half-planes left of every edge of the convex,
// counter-clockwise `clip` (Sutherland-Hodgman). A `clip` of fewer than three points has no
// edges to clip by: `subject` is returned as it is.
inline std::vector<Point2d> clip_convex2(std::vector<Point2d> subject, const std::vector<Point2d>& clip) {
  const std::size_t m = clip.size();
  for (std::size_t e = 0; e < m && m >= 3 && !subject.empty(); ++e) {
    const Point2d &a = clip[e], &b = clip[(e + 1) % m];
    const auto side = [&](const Point2d& q) { return (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]); };
    std::vector<Point2d> kept;
    for (std::size_t i = 0; i < subject.size(); ++i) {
      const Point2d &p = subject[i], &q = subject[(i + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) kept.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) {
        const double t = sp / (sp - sq);
        kept.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
    subject = std::move(kept);
  }
  return subject;
}

}  // namespace rockcontact::kernel::detail
