#pragma once
// Demarcation points: where a segment inside a convex polygon is cut into pieces on which the
// potential phi is linear (seed 000 §3.2.3), so the trapezoid rule (eq. 16) is exact per piece.
//
// Two modes:
//   exact  the breakpoints of the lower envelope of the edge-distance functions along the
//          segment, i.e. the true kinks of d_exit (where the segment crosses the medial axis).
//          With them eq. 18 integrates phi without error.
//   paper  the paper's construction: the centre of the segment plus its crossings with the
//          angle-bisector ray of every node (the medial-axis branches that touch the boundary);
//          for an edge shorter than `small_edge` the bisector rays of its two end nodes stop
//          where they meet (a virtual node) and one ray continues from there, bisecting the two
//          neighbouring edges. Interior medial-axis branches (polygons with more than three
//          edges whose bisectors do not meet in one point) are not represented, so on such
//          polygons the paper mode integrates with a small error; that is the paper's method,
//          kept for comparison.
//
// Departure from the paper: the paper adds the begin and end points of the segment and its
// centre; here only interior parameters are returned (0 < t < 1, sorted, distinct); callers add
// the end points themselves.

#include <string_view>
#include <optional>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

enum class Demarcation { paper, exact };

constexpr std::string_view to_string(Demarcation d) {
  return d == Demarcation::paper ? "paper" : "exact";
}

constexpr std::optional<Demarcation> parse_demarcation(std::string_view text) {
  if (text == "paper") return Demarcation::paper;
  if (text == "exact") return Demarcation::exact;
  return std::nullopt;
}

// Parameters t in (0, 1) of the demarcation points on the segment a + t (b - a), which must lie
// in `polygon` (closed). `small_edge` (m) is used by the paper mode only. Evaluated in double.
std::vector<double> demarcation_parameters(const ConvexPolygon& polygon, const Point2& a,
                                           const Point2& b, Demarcation mode, double small_edge);

}  // namespace rockcontact::kernel
