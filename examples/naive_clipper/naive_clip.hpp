#pragma once
// The naive clip of naive_clipper.cpp, kept apart so the peer benchmark (bench/peer_bench.cpp)
// times exactly the kernel this example checks: Sutherland-Hodgman in plain double, `subject`
// clipped by each edge half-plane of the CCW polygon `clip`. A point on a clipping line counts as
// inside (cross product >= 0), an edge crossing is cut at the parameter s_p / (s_p - s_q) of the
// two side values; no tolerance, nothing certified. Any point type with double members x, y.

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

namespace naive {

// The clipped polygon into `out`; `scratch` is reused between edges, so with both vectors kept
// across calls nothing is allocated once they have grown.
template <class Point>
void clip_polygon(std::span<const Point> clip, std::span<const Point> subject, std::vector<Point>& out,
                  std::vector<Point>& scratch) {
  out.assign(subject.begin(), subject.end());
  for (std::size_t i = 0; i < clip.size() && !out.empty(); ++i) {
    const Point a = clip[i];
    const Point b = clip[i + 1 == clip.size() ? 0 : i + 1];
    const auto side = [&](const Point& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    scratch.clear();
    Point p = out.back();
    double sp = side(p);
    for (const Point& q : out) {
      const double sq = side(q);
      if ((sp >= 0.0) != (sq >= 0.0)) {
        const double t = sp / (sp - sq);
        scratch.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
      }
      if (sq >= 0.0) scratch.push_back(q);
      p = q;
      sp = sq;
    }
    std::swap(out, scratch);
  }
}

}  // namespace naive
