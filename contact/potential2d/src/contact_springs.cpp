#include "rockcontact/contact/potential2d/contact_springs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcontact::contact {
namespace {

using kernel::ConvexPolygon;
using kernel::Point2;
using kernel::Vector2;

// Of an edge's length: how near its end a point counts as at the end.
constexpr double corner_fraction = 1.0e-9;

// The edge of `face` (CCW) whose outward normal separates `other` the most: its index and the
// signed distance of `other` from its line.
struct Axis {
  std::size_t edge = 0;
  double distance = -std::numeric_limits<double>::infinity();
};

Axis best_axis(const ConvexPolygon& face, const ConvexPolygon& other) {
  Axis best;
  for (std::size_t e = 0; e < face.size(); ++e) {
    const Point2 p = face[e], q = face[face.next(e)];
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    const Vector2 n{(q.y - p.y) / len, -(q.x - p.x) / len};
    double nearest = std::numeric_limits<double>::infinity();
    for (const Point2& v : other.vertices()) nearest = std::min(nearest, (v.x - p.x) * n.x + (v.y - p.y) * n.y);
    if (nearest > best.distance) best = {e, nearest};
  }
  return best;
}

// The line on edge `axis.edge` of `face` facing `other` (contact_line, header), with the normal
// outward of `face`.
std::optional<ContactLine> line_on(const ConvexPolygon& face, const ConvexPolygon& other, const Axis& axis) {
  const Point2 p = face[axis.edge], q = face[face.next(axis.edge)];
  const double len = std::hypot(q.x - p.x, q.y - p.y);
  const Vector2 t{(q.x - p.x) / len, (q.y - p.y) / len};
  const Vector2 n{t.y, -t.x};
  // The other's edge most opposed to n; at a tie (a vertex on the face, its two edges equally
  // opposed) the one reaching deeper.
  std::size_t best = 0;
  double opposed = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < other.size(); ++e) {
    const Point2 a = other[e], b = other[other.next(e)];
    const double l = std::hypot(b.x - a.x, b.y - a.y);
    const double c = ((b.y - a.y) * n.x - (b.x - a.x) * n.y) / l;  // its outward normal . n
    if (c < opposed) opposed = c, best = e;
  }
  const Point2 a = other[best], b = other[other.next(best)];
  // Along the face: u; across: g (signed distance from the face's line, along n).
  const auto u_of = [&](Point2 v) { return (v.x - p.x) * t.x + (v.y - p.y) * t.y; };
  const auto g_of = [&](Point2 v) { return (v.x - p.x) * n.x + (v.y - p.y) * n.y; };
  double ua = u_of(a), ub = u_of(b), ga = g_of(a), gb = g_of(b);
  if (ua > ub) std::swap(ua, ub), std::swap(ga, gb);
  const double lo = std::max(ua, 0.0), hi = std::min(ub, len);
  const double end = corner_fraction * len;
  if (hi - lo <= end && axis.distance >= 0.0) return std::nullopt;  // corners that meet
  const auto gap_at = [&](double u) { return ub > ua ? ga + (gb - ga) * (u - ua) / (ub - ua) : std::min(ga, gb); };
  double from = lo, to = std::max(hi, lo);
  return ContactLine{{p.x + from * t.x, p.y + from * t.y}, {p.x + to * t.x, p.y + to * t.y}, n,
                     gap_at(from), gap_at(to)};
}

}  // namespace

std::optional<ContactLine> contact_line(const ConvexPolygon& a, const ConvexPolygon& b, double reach) {
  const Axis on_a = best_axis(a, b), on_b = best_axis(b, a);
  const bool a_face = on_a.distance >= on_b.distance;
  const Axis& axis = a_face ? on_a : on_b;
  if (axis.distance > reach) return std::nullopt;
  if (!a_face) return line_on(b, a, axis);  // b's outward normal: from b towards a
  std::optional<ContactLine> line = line_on(a, b, axis);
  if (line) line->normal = {-line->normal.x, -line->normal.y};
  return line;
}

Interval closed_part(const ContactLine& line, double moved_from, double moved_to) {
  const double g0 = line.gap_from + moved_from, g1 = line.gap_to + moved_to;
  if (g0 < 0.0 && g1 < 0.0) return {0.0, 1.0};
  if (g0 >= 0.0 && g1 >= 0.0) return {};
  const double zero = g0 / (g0 - g1);  // where the gap changes sign
  return g0 < 0.0 ? Interval{0.0, zero} : Interval{zero, 1.0};
}

std::array<GaussSpring, 2> gauss_springs(const ContactLine& line, Interval part, double kn, double H) {
  const double length = std::hypot(line.to.x - line.from.x, line.to.y - line.from.y) * (part.last - part.first);
  const double half = 0.5 / std::sqrt(3.0);
  std::array<GaussSpring, 2> out;
  for (std::size_t k = 0; k < 2; ++k) {
    const double s = part.first + (part.last - part.first) * (0.5 + (k == 0 ? -half : half));
    out[k].at = {line.from.x + s * (line.to.x - line.from.x), line.from.y + s * (line.to.y - line.from.y)};
    out[k].gap = line.gap_from + s * (line.gap_to - line.gap_from);
    out[k].k = kn * length / H;
  }
  return out;
}

double part_force_change(const ContactLine& line, Interval a, Interval b, double kn, double H,
                         double moved_from, double moved_to) {
  const double g0 = line.gap_from + moved_from, g1 = line.gap_to + moved_to;
  // The integral of |g| over [t0, t1] (fractions of the line), g linear from g0 at 0 to g1 at 1.
  const auto magnitude = [&](double t0, double t1) {
    if (!(t0 < t1)) return 0.0;
    const double u = g0 + (g1 - g0) * t0, v = g0 + (g1 - g0) * t1;
    if ((u < 0.0) == (v < 0.0)) return 0.5 * (std::abs(u) + std::abs(v)) * (t1 - t0);
    const double zero = t0 + (t1 - t0) * u / (u - v);
    return 0.5 * (std::abs(u) * (zero - t0) + std::abs(v) * (t1 - zero));
  };
  double changed = 0.0;
  if (a.empty() || b.empty() || std::max(a.first, b.first) >= std::min(a.last, b.last)) {
    // Disjoint (or one empty): all of both.
    if (!a.empty()) changed += magnitude(a.first, a.last);
    if (!b.empty()) changed += magnitude(b.first, b.last);
  } else {
    // Overlapping: the two end pieces of their union outside their intersection.
    changed = magnitude(std::min(a.first, b.first), std::max(a.first, b.first)) +
              magnitude(std::min(a.last, b.last), std::max(a.last, b.last));
  }
  const double length = std::hypot(line.to.x - line.from.x, line.to.y - line.from.y);
  return 2.0 * kn / H * length * changed;
}

}  // namespace rockcontact::contact
