#include "rockcontact/generators/pair_generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"
#include "rng.hpp"

namespace rockcontact::robustness {
namespace {

using detail::mix;
using detail::Rng;
using kernel::Sign;
using Polygon = std::vector<Point2>;

// Exact orientation (the kernel's filtered predicate, exact by contract and checked against
// GMP in kernel/2d/tests/predicates_test.cpp).
Sign orient(const Point2& p, const Point2& q, const Point2& r) {
  return kernel::orientation<kernel::Filtered>(p, q, r);
}

// ---- vectors without libm ----------------------------------------------------------------

Vector2 operator-(const Point2& a, const Point2& b) { return {a.x - b.x, a.y - b.y}; }
Vector2 operator*(double s, const Vector2& v) { return {s * v.x, s * v.y}; }
Vector2 operator+(const Vector2& a, const Vector2& b) { return {a.x + b.x, a.y + b.y}; }
Vector2 operator-(const Vector2& v) { return {-v.x, -v.y}; }
Point2 operator+(const Point2& p, const Vector2& v) { return {p.x + v.x, p.y + v.y}; }
double dot(const Vector2& a, const Vector2& b) { return a.x * b.x + a.y * b.y; }
double length(const Vector2& v) { return std::sqrt(dot(v, v)); }
Vector2 unit(const Vector2& v) { return (1.0 / length(v)) * v; }
Vector2 left_normal(const Vector2& v) { return {-v.y, v.x}; }
Vector2 right_normal(const Vector2& v) { return {v.y, -v.x}; }

// v turned counter-clockwise by 2 atan(t): the rational parametrisation of the circle.
// t = 1 is a quarter turn, t = -1 a quarter turn clockwise, small t turns by about 2t.
Vector2 rotate(const Vector2& v, double t) {
  const double d = 1.0 + t * t;
  const double c = (1.0 - t * t) / d, s = 2.0 * t / d;
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

Vector2 random_direction(Rng& rng) {
  const Vector2 v = rotate({1.0, 0.0}, rng.uniform(-1.0, 1.0));
  return rng.chance(0.5) ? v : -v;
}

// A direction in the open half-plane on the right of u, at least ~3.4° from u's line.
Vector2 rightward(Rng& rng, const Vector2& u) {
  return rotate(right_normal(u), rng.uniform(-0.95, 0.95));
}

// A direction in a 164° arc that starts 5.7° to 53° left of u and sweeps clockwise: points
// placed along such directions from a vertex keep that vertex extreme (the arc is < 180°).
Vector2 turned_in(Rng& rng, const Vector2& u, double max_start) {
  const Vector2 start = rotate(u, rng.uniform(0.05, max_start));
  return rotate(rotate(start, -1.0), rng.uniform(-0.75, 1.0));
}

double snap(double x, int grid_exponent) {
  return std::ldexp(std::round(std::ldexp(x, -grid_exponent)), grid_exponent);
}
Point2 snap(const Point2& p, int grid_exponent) {
  return {snap(p.x, grid_exponent), snap(p.y, grid_exponent)};
}

// A recipe's numbers: printf's %g and %.17g round correctly, so the text is the same on
// every platform.
template <class... Args>
std::string format(const char* pattern, Args... args) {
  std::array<char, 200> buffer{};
  std::snprintf(buffer.data(), buffer.size(), pattern, args...);
  return buffer.data();
}

[[noreturn]] void generator_bug(const std::string& what) {
  throw std::logic_error("pair generator: " + what);
}

bool contains_vertex(const Polygon& poly, const Point2& p) {
  return std::find(poly.begin(), poly.end(), p) != poly.end();
}

// True when poly has the edge from -> to (consecutive in CCW order).
bool has_edge(const Polygon& poly, const Point2& from, const Point2& to) {
  for (std::size_t k = 0; k < poly.size(); ++k) {
    if (poly[k] == from && poly[(k + 1) % poly.size()] == to) return true;
  }
  return false;
}

Point2 vertex_mean(const Polygon& poly) {
  double x = 0.0, y = 0.0;
  for (const Point2& p : poly) x += p.x, y += p.y;
  const double n = static_cast<double>(poly.size());
  return {x / n, y / n};
}

// The vertex of poly farthest along u.
const Point2& support_vertex(const Polygon& poly, const Vector2& u) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < poly.size(); ++k) {
    if (dot(poly[k] - poly[best], u) > 0.0) best = k;
  }
  return poly[best];
}

// Largest distance from the vertex mean to a vertex (m).
double radius(const Polygon& poly) {
  const Point2 c = vertex_mean(poly);
  double best = 0.0;
  for (const Point2& p : poly) best = std::max(best, length(p - c));
  return best;
}

Polygon translated(const Polygon& poly, const Vector2& shift) {
  Polygon out;
  for (const Point2& p : poly) out.push_back(p + shift);
  return convex_hull(std::move(out));
}

// tp moved so that its vertex farthest along -u sits at cp's vertex farthest along u, plus
// `gap` along u (m; negative pushes it into cp) and `lateral` across u (m).
Polygon place_at_gap(const Polygon& cp, const Polygon& tp, const Vector2& u, double gap, double lateral) {
  const Point2 target = support_vertex(cp, u) + gap * u + lateral * left_normal(u);
  return translated(tp, target - support_vertex(tp, -u));
}

// ---- polygons -----------------------------------------------------------------------------

// 3..max_vertices points on an ellipse of diameter ~size about `centre`, randomly turned.
Polygon random_convex(Rng& rng, const Point2& centre, int max_vertices, double size) {
  const auto n = rng.integer(3, max_vertices);
  const double a = size * rng.uniform(0.35, 0.6), b = size * rng.uniform(0.35, 0.6);
  const Vector2 axis = random_direction(rng);
  Polygon points;
  for (std::int64_t k = 0; k < n; ++k) {
    const Vector2 d = random_direction(rng);
    const Vector2 local{a * d.x, b * d.y};
    points.push_back(centre + Vector2{axis.x * local.x - axis.y * local.y,
                                      axis.y * local.x + axis.x * local.y});
  }
  return convex_hull(std::move(points));
}

Point2 random_point(Rng& rng, double half_width) {
  return {rng.uniform(-half_width, half_width), rng.uniform(-half_width, half_width)};
}

// A polygon that has the vertex c of cp and otherwise lies strictly on the right of the line
// (p, q) through c: it touches cp (which lies on the left, closed) at c only.
// Snapped to the grid 2^*grid_exponent when one is given.
Polygon outside_at(Rng& rng, const Point2& c, const Point2& p, const Point2& q,
                   std::optional<int> grid_exponent) {
  const Vector2 u = unit(q - p);
  Polygon points{c};
  const auto count = rng.integer(2, 6);
  for (std::int64_t k = 0; k < count; ++k) {
    const Vector2 direction = rightward(rng, u);
    Point2 x = c + rng.uniform(0.2, 1.0) * direction;
    if (grid_exponent) x = snap(x, *grid_exponent);
    if (orient(p, q, x) == Sign::negative) points.push_back(x);
  }
  return convex_hull(std::move(points));
}

// Half of the near-contact placements meet corner to corner, half up to 0.2 m aside.
double lateral_offset(Rng& rng) { return rng.chance(0.5) ? 0.0 : rng.uniform(-0.2, 0.2); }

bool valid(const Polygon& poly) { return poly.size() >= 3; }

std::optional<PolygonPair> pair_if_valid(Polygon cp, Polygon tp) {
  if (!valid(cp) || !valid(tp)) return std::nullopt;
  return PolygonPair{std::move(cp), std::move(tp), {}};
}

// ---- families -----------------------------------------------------------------------------

std::optional<PolygonPair> random_pair(Rng& rng) {
  Polygon cp = random_convex(rng, random_point(rng, 0.5), 10, 1.0);
  if (!valid(cp)) return std::nullopt;
  const double mode = rng.unit();
  if (mode < 0.2) {
    const std::size_t i = rng.index(cp.size());
    const Point2 c = cp[i], next = cp[(i + 1) % cp.size()];
    Polygon tp = outside_at(rng, c, c, next, std::nullopt);
    return pair_if_valid(std::move(cp), std::move(tp));
  }
  const Polygon local = random_convex(rng, {0.0, 0.0}, 10, 1.0);
  if (!valid(local)) return std::nullopt;
  const Vector2 u = random_direction(rng);
  if (mode < 0.4) {
    const double lateral = lateral_offset(rng);
    return pair_if_valid(cp, place_at_gap(cp, local, u, rng.uniform(-0.02, 0.02), lateral));
  }
  const double distance = rng.uniform(0.0, 0.9) * (radius(cp) + radius(local));
  return pair_if_valid(cp, translated(local, (vertex_mean(cp) - Point2{}) + distance * u));
}

// A random polygon with every corner cut by a chamfer edge of about 0.01 m.
Polygon chamfered(Rng& rng, const Point2& centre) {
  const Polygon base = random_convex(rng, centre, 8, 1.0);
  Polygon points;
  for (std::size_t i = 0; i < base.size(); ++i) {
    const Point2& v = base[i];
    const Vector2 to_prev = base[(i + base.size() - 1) % base.size()] - v;
    const Vector2 to_next = base[(i + 1) % base.size()] - v;
    const Vector2 ua = unit(to_prev), ub = unit(to_next);
    // The chamfer joins v + d ua and v + d ub, a chord of length d |ua - ub|.
    const double d = std::min(0.01 / length(ua + -ub), 0.3 * std::min(length(to_prev), length(to_next)));
    points.push_back(v + d * ua);
    points.push_back(v + d * ub);
  }
  return convex_hull(std::move(points));
}

std::optional<PolygonPair> short_edges_pair(Rng& rng) {
  Polygon cp = chamfered(rng, random_point(rng, 0.5));
  const Polygon local = chamfered(rng, {0.0, 0.0});
  if (!valid(cp) || !valid(local)) return std::nullopt;
  const double lateral = lateral_offset(rng);
  const double gap = rng.uniform(-0.02, 0.005);
  Polygon tp = place_at_gap(cp, local, random_direction(rng), gap, lateral);
  return pair_if_valid(std::move(cp), std::move(tp));
}

// Apex, two base corners at `length` along the axis, half-width length * half_tan, and a blunt
// back vertex `back` further along the axis when back > 0.
Polygon wedge(const Point2& apex, const Vector2& axis, double half_tan, double length, double back) {
  const Vector2 n = left_normal(axis);
  Polygon points{apex, apex + length * (axis + -half_tan * n), apex + length * (axis + half_tan * n)};
  if (back > 0.0) points.push_back(apex + (length + back) * axis);
  return convex_hull(std::move(points));
}

// tan of half the apex angle: tan(2.5°) and tan(0.25°).
constexpr double tan_half_5deg = 0.04366094290851206;
constexpr double tan_half_0_5deg = 0.004363350820701567;

std::optional<PolygonPair> wedge_pair(Rng& rng, double half_tan) {
  const auto blunt = [&](double length) {
    return rng.chance(0.5) ? length * half_tan * rng.uniform(0.2, 2.0) : 0.0;
  };
  const Point2 apex = random_point(rng, 0.5);
  const Vector2 axis = random_direction(rng);
  const double length = rng.uniform(0.8, 1.2);
  Polygon cp = wedge(apex, axis, half_tan, length, blunt(length));
  // tp's tip: `depth` along cp's axis (negative = short of cp's apex), within about its width.
  const double depth = rng.uniform(-0.05, 0.3) * length;
  const double lateral = rng.uniform(-1.5, 1.5) * std::fabs(depth) * half_tan;
  const Point2 tip = apex + depth * axis + lateral * left_normal(axis);
  // Mostly anti-parallel within about one apex angle; a quarter cross at up to ~60°.
  const double turn = rng.chance(0.75) ? rng.uniform(-half_tan, half_tan) : rng.uniform(-0.6, 0.6);
  const double tp_length = rng.uniform(0.8, 1.2);
  Polygon tp = wedge(tip, rotate(-axis, turn), half_tan, tp_length, blunt(tp_length));
  return pair_if_valid(std::move(cp), std::move(tp));
}

// A random edge of `poly` at least 0.1 m long, else its longest: the edge a near-parallel
// partner is laid against.
std::size_t long_edge(Rng& rng, const Polygon& poly) {
  const auto edge_length = [&](std::size_t i) { return length(poly[(i + 1) % poly.size()] - poly[i]); };
  std::size_t k = rng.index(poly.size());
  if (edge_length(k) < 0.1) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      if (edge_length(i) > edge_length(k)) k = i;
    }
  }
  return k;
}

std::optional<PolygonPair> near_parallel_pair(Rng& rng) {
  Polygon cp = random_convex(rng, random_point(rng, 0.5), 10, 1.0);
  if (!valid(cp)) return std::nullopt;
  const std::size_t k = long_edge(rng, cp);
  const Vector2 e = cp[(k + 1) % cp.size()] - cp[k];
  const Vector2 outward = right_normal(unit(e));
  // tp's edge P0 -> P1 runs against e, turned by ~angle; tp lies on its left, outside cp.
  const double angle_sign = rng.sign();
  const double angle = angle_sign * rng.octaves(-39, -21);
  const Vector2 d = rotate(-unit(e), angle / 2.0);
  double offset = 0.0;
  if (!rng.chance(0.1)) {
    const double offset_sign = rng.sign();
    offset = offset_sign * rng.octaves(-50, -20);
  }
  const Point2 p0 = cp[k] + rng.uniform(0.2, 1.5) * e + offset * outward;
  const double tp_length = rng.uniform(0.3, 1.2);
  Polygon points{p0, p0 + tp_length * d};
  const auto extra = rng.integer(1, 5);
  for (std::int64_t i = 0; i < extra; ++i) {
    const double across = rng.uniform(0.1, 0.8);
    points.push_back(p0 + rng.uniform(0.1, 0.9) * tp_length * d + across * left_normal(d));
  }
  return pair_if_valid(std::move(cp), convex_hull(std::move(points)));
}

// ---- slivers ------------------------------------------------------------------------------

// Thin polygons laid along a unit axis from a tip: the points tip + a axis + b n, n the left
// normal, for the shape's local (a, b) with 0 <= a <= length and |b| <= h = width / 2. The
// pointed shapes have the local point (0, 0), which is `tip` exactly (tip + 0 = tip), with a
// half-angle below atan(2 / aspect) <= 1.2°; the rectangle has no vertex there. Every shape
// contains the midline points tip + a axis, 0.2 length <= a <= 0.8 length, at least 0.1 width
// from its boundary. diameter / width is the aspect (hexagon), aspect + 1 / (4 aspect)
// (triangle) or sqrt(aspect^2 + 1) (diamond, rectangle): within 1e-12 relative of it.
enum class SliverShape : std::uint8_t { triangle, diamond, hexagon, rectangle };

constexpr std::array<const char*, 4> sliver_shape_names{"triangle", "diamond", "hexagon", "rectangle"};

struct SliverSpec {
  SliverShape shape;
  double length;  // m
  double aspect;  // length / width
};

struct Sliver {
  Polygon polygon;
  Point2 tip;
  Vector2 axis;
  SliverSpec spec;
};

SliverSpec draw_sliver_spec(Rng& rng, bool pointed) {
  const auto shape = static_cast<SliverShape>(rng.index(pointed ? 3 : 4));
  const double length = rng.uniform(0.5, 1.5);
  return {shape, length, rng.log_uniform(1e2, 1e6)};
}

Sliver make_sliver(const SliverSpec& spec, const Point2& tip, const Vector2& axis) {
  const double l = spec.length, h = 0.5 * spec.length / spec.aspect;
  const Vector2 n = left_normal(axis);
  Polygon points;
  const auto add = [&](std::initializer_list<std::array<double, 2>> local) {
    for (const auto& [a, b] : local) points.push_back(tip + (a * axis + b * n));
  };
  switch (spec.shape) {
    case SliverShape::triangle: add({{0, 0}, {l, -h}, {l, h}}); break;
    case SliverShape::diamond: add({{0, 0}, {l / 2, -h}, {l, 0}, {l / 2, h}}); break;
    case SliverShape::hexagon: add({{0, 0}, {l / 4, -h}, {3 * l / 4, -h}, {l, 0}, {3 * l / 4, h}, {l / 4, h}}); break;
    case SliverShape::rectangle: add({{0, -h}, {l, -h}, {l, h}, {0, h}}); break;
  }
  return {convex_hull(std::move(points)), tip, axis, spec};
}

// A sliver whose midline point at half its length is (to rounding) `centre`.
Sliver sliver_about(const SliverSpec& spec, const Point2& centre, const Vector2& axis) {
  return make_sliver(spec, centre + (-0.5 * spec.length) * axis, axis);
}

// A sliver of any (or a pointed) shape about a random point, along a random direction.
Sliver random_sliver(Rng& rng, bool pointed) {
  const SliverSpec spec = draw_sliver_spec(rng, pointed);
  const Point2 centre = random_point(rng, 0.5);
  return sliver_about(spec, centre, random_direction(rng));
}

Point2 on_midline(const Sliver& s, double fraction) { return s.tip + (fraction * s.spec.length) * s.axis; }

std::string describe(const Sliver& s) {
  return format("sliver aspect %.4g %s", s.spec.aspect, sliver_shape_names[static_cast<std::size_t>(s.spec.shape)]);
}

// The two polygons of a sliver pair before cp and tp are assigned: `second` was placed
// against `first`.
struct Placed {
  Polygon first;
  std::string first_text;
  Polygon second;
  std::string second_text;
  std::string placement;
};

const std::string ordinary_text = "ordinary";

// Both polygons contain the point p well inside, so they overlap whatever the rounding.
Placed slivers_crossing(Rng& rng, bool two_slivers) {
  const SliverSpec spec = draw_sliver_spec(rng, false);
  const Vector2 axis = random_direction(rng);
  if (two_slivers) {
    const Point2 p = random_point(rng, 0.5);
    const Sliver a = sliver_about(spec, p, axis);
    // At 2.3° to 90° to the first.
    const SliverSpec other = draw_sliver_spec(rng, false);
    const double sign = rng.sign();
    const Sliver b = sliver_about(other, p, rotate(axis, sign * rng.uniform(0.02, 1.0)));
    return {a.polygon, describe(a), b.polygon, describe(b), "crossing"};
  }
  // The ordinary polygon lies within 1.2 * 0.6 * 0.35 = 0.42 length of its vertex mean p (an
  // interior point), so the sliver, centred at p, runs through it and out on both sides.
  const Polygon o = random_convex(rng, random_point(rng, 0.5), 10, 0.35 * spec.length);
  const Sliver s = sliver_about(spec, vertex_mean(o), axis);
  return {o, ordinary_text, s.polygon, describe(s), "crossing"};
}

// A pointed sliver's tip strictly inside the first polygon.
Placed slivers_overlapping(Rng& rng, bool two_slivers) {
  if (two_slivers) {
    const Sliver a = random_sliver(rng, false);
    const Point2 q = on_midline(a, rng.uniform(0.2, 0.8));
    // Nearly along a, either way, within about twice b's own tip half-angle: the edges of the
    // two are nearly parallel and cross at grazing angles.
    const SliverSpec spec = draw_sliver_spec(rng, true);
    const Vector2 along_a = rng.sign() * a.axis;
    const Sliver b = make_sliver(spec, q, rotate(along_a, rng.uniform(-2.0, 2.0) / spec.aspect));
    return {a.polygon, describe(a), b.polygon, describe(b), "overlapping"};
  }
  const Polygon o = random_convex(rng, random_point(rng, 0.5), 10, 1.0);
  const Point2 mean = vertex_mean(o);
  const Point2& corner = o[rng.index(o.size())];
  const Point2 q = mean + rng.uniform(0.0, 0.8) * (corner - mean);
  const SliverSpec spec = draw_sliver_spec(rng, true);
  const Sliver s = make_sliver(spec, q, random_direction(rng));
  return {o, ordinary_text, s.polygon, describe(s), "overlapping"};
}

// The second polygon has the vertex c of the first and otherwise lies strictly on the right of
// the first's edge line c -> next (checked exactly): they touch at c only. A pointed sliver
// leaves c at >= 3° to that line (rightward) with a half-angle <= 1.2°.
Placed slivers_touching(Rng& rng, bool two_slivers) {
  const bool sliver_first = two_slivers || rng.chance(0.5);
  Polygon first;
  std::string first_text = ordinary_text;
  if (sliver_first) {
    const Sliver a = random_sliver(rng, false);
    first = a.polygon;
    first_text = describe(a);
  } else {
    first = random_convex(rng, random_point(rng, 0.5), 10, 1.0);
  }
  const std::size_t i = rng.index(first.size());
  const Point2 c = first[i], next = first[(i + 1) % first.size()];
  Polygon second;
  std::string second_text = ordinary_text;
  if (two_slivers || !sliver_first) {
    const SliverSpec spec = draw_sliver_spec(rng, true);
    const Sliver b = make_sliver(spec, c, rightward(rng, unit(next - c)));
    second = b.polygon;
    second_text = describe(b);
    for (const Point2& v : second) {
      if (v != c && orient(c, next, v) != Sign::negative) generator_bug("touching sliver crosses the edge line");
    }
  } else {
    second = outside_at(rng, c, c, next, std::nullopt);
  }
  return {first, first_text, second, second_text, "touching"};
}

// The second polygon moved so that its extreme vertex along -u is a small gap beyond the
// first's extreme vertex along u: separated by a line, the gap (>= 2^-40 m) far above the
// ~1e-15 m rounding of the placement.
Placed slivers_separated(Rng& rng, bool two_slivers) {
  const bool sliver_first = two_slivers || rng.chance(0.5);
  const auto make = [&](bool sliver, const Point2& centre, std::string& text) {
    if (!sliver) return random_convex(rng, centre, 10, 1.0);
    const SliverSpec spec = draw_sliver_spec(rng, false);
    const Sliver s = sliver_about(spec, centre, random_direction(rng));
    text = describe(s);
    return s.polygon;
  };
  std::string first_text = ordinary_text, second_text = ordinary_text;
  const Polygon first = make(sliver_first, random_point(rng, 0.5), first_text);
  const Polygon local = make(two_slivers || !sliver_first, {0.0, 0.0}, second_text);
  const double gap = rng.octaves(-40, -8);
  const Vector2 u = random_direction(rng);
  const Polygon second = place_at_gap(first, local, u, gap, lateral_offset(rng));
  return {first, first_text, second, second_text, format("separated, gap %.3g m", gap)};
}

std::optional<PolygonPair> sliver_pair(Rng& rng) {
  const auto placement = rng.index(4);
  const bool two_slivers = rng.chance(0.5);
  Placed placed = placement == 0   ? slivers_crossing(rng, two_slivers)
                  : placement == 1 ? slivers_overlapping(rng, two_slivers)
                  : placement == 2 ? slivers_touching(rng, two_slivers)
                                   : slivers_separated(rng, two_slivers);
  const bool second_is_tp = rng.chance(0.5);
  std::optional<PolygonPair> pair = second_is_tp ? pair_if_valid(std::move(placed.first), std::move(placed.second))
                                                 : pair_if_valid(std::move(placed.second), std::move(placed.first));
  if (!pair) return std::nullopt;
  const std::string& cp_text = second_is_tp ? placed.first_text : placed.second_text;
  const std::string& tp_text = second_is_tp ? placed.second_text : placed.first_text;
  pair->recipe = "cp " + cp_text + ", tp " + tp_text + ", placement " + placed.placement;
  return pair;
}

// ---- fine wedges and tiny edges -----------------------------------------------------------

// tan x for |x| <= 0.01 by its Taylor series x + x^3/3 + 2 x^5/15 + 17 x^7/315; the first
// term left out, 62 x^9/2835, is below 3e-20 x.
double small_tan(double x) {
  const double x2 = x * x;
  return x * (1.0 + x2 * (1.0 / 3.0 + x2 * (2.0 / 15.0 + x2 * (17.0 / 315.0))));
}

constexpr double degree = std::numbers::pi / 180.0;

// cp a wedge; tp's tip at depth (in units of cp's local half-width, negative = outside) across
// cp's left side at a fraction of its length, tp's axis leaving cp at 6° to 90° to that side.
std::optional<PolygonPair> wedge_into_side(Rng& rng, double half_tan, double& depth) {
  const double blunt = rng.chance(0.5) ? rng.uniform(0.2, 2.0) : 0.0;
  const Point2 apex = random_point(rng, 0.5);
  const Vector2 axis = random_direction(rng);
  const double length = rng.uniform(0.8, 1.2);
  Polygon cp = wedge(apex, axis, half_tan, length, length * half_tan * blunt);
  const Vector2 side = axis + half_tan * left_normal(axis);
  const Vector2 outward = unit(left_normal(side));
  const double fraction = rng.uniform(0.2, 0.9);
  depth = rng.uniform(-0.5, 1.0);
  const Point2 tip = apex + (fraction * length) * side + (-depth * fraction * length * half_tan) * outward;
  const double tp_length = rng.uniform(0.8, 1.2);
  const double tp_back = rng.chance(0.5) ? tp_length * half_tan * rng.uniform(0.2, 2.0) : 0.0;
  Polygon tp = wedge(tip, rotate(outward, rng.uniform(-0.9, 0.9)), half_tan, tp_length, tp_back);
  return pair_if_valid(std::move(cp), std::move(tp));
}

std::optional<PolygonPair> fine_wedge_pair(Rng& rng) {
  const double angle = rng.log_uniform(0.1 * degree, 1.0 * degree);
  const double half_tan = small_tan(angle / 2.0);
  const std::string text = format("angle_deg %.6g", angle / degree);
  if (rng.chance(0.5)) {
    std::optional<PolygonPair> pair = wedge_pair(rng, half_tan);
    if (pair) pair->recipe = text + ", tip into tip";
    return pair;
  }
  double depth = 0.0;
  std::optional<PolygonPair> pair = wedge_into_side(rng, half_tan, depth);
  if (pair) pair->recipe = text + format(", tip into a side, depth %.3g of its half-width", depth);
  return pair;
}

// Largest vertex distance (m).
double diameter(const Polygon& poly) {
  double best = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    for (std::size_t j = i + 1; j < poly.size(); ++j) best = std::max(best, length(poly[j] - poly[i]));
  }
  return best;
}

// A random polygon with every corner cut by a chamfer chord of `relative` times its diameter
// D (relative <= 1e-2), or nullopt when the polygon has a corner below 29° (|ua - ub| < 0.5)
// or an edge below 0.05 D. Those bounds make the chamfers exact in length: each chamfer end
// is d = relative D / |ua - ub| <= 2 relative D <= 0.02 D from its corner, so every original
// edge keeps >= 0.05 D - 0.04 D = 0.01 D >= relative D, the shortest edge is a chamfer chord,
// and the diameter shrinks by at most 4 relative D.
std::optional<Polygon> tiny_chamfered(Rng& rng, const Point2& centre, double relative) {
  const Polygon base = random_convex(rng, centre, 8, 1.0);
  const double size = diameter(base);
  Polygon points;
  for (std::size_t i = 0; i < base.size(); ++i) {
    const Point2& v = base[i];
    const Vector2 to_prev = base[(i + base.size() - 1) % base.size()] - v;
    const Vector2 to_next = base[(i + 1) % base.size()] - v;
    const double spread = length(unit(to_prev) + -unit(to_next));
    if (spread < 0.5 || length(to_next) < 0.05 * size) return std::nullopt;
    const double d = relative * size / spread;
    points.push_back(v + d * unit(to_prev));
    points.push_back(v + d * unit(to_next));
  }
  Polygon hull = convex_hull(std::move(points));
  if (hull.size() != 2 * base.size()) return std::nullopt;
  return hull;
}

std::optional<PolygonPair> tiny_edges_pair(Rng& rng) {
  const double relative = rng.log_uniform(1e-6, 1e-2);
  std::optional<Polygon> cp = tiny_chamfered(rng, random_point(rng, 0.5), relative);
  if (!cp) return std::nullopt;
  const std::optional<Polygon> local = tiny_chamfered(rng, {0.0, 0.0}, relative);
  if (!local) return std::nullopt;
  // Corner to corner at the chamfers' scale: a gap of -2 to +1 chamfer, laterally 0 or within
  // 3 chamfers.
  const double chamfer = relative * diameter(*cp);
  const double gap = rng.uniform(-2.0, 1.0) * chamfer;
  const double lateral = rng.chance(0.5) ? 0.0 : rng.uniform(-3.0, 3.0) * chamfer;
  Polygon tp = place_at_gap(*cp, *local, random_direction(rng), gap, lateral);
  std::optional<PolygonPair> pair = pair_if_valid(std::move(*cp), std::move(tp));
  if (pair) pair->recipe = format("chamfer %.4g of the diameter, gap %.3g m, lateral %.3g m", relative, gap, lateral);
  return pair;
}

// ---- dyadic families ------------------------------------------------------------------------

// Grid of the points of the exact families (m). Multiples of 2^-50 below 4 in magnitude need at
// most 52 significant bits, so the sums A + s (B - A) below are exact, while the products
// inside the predicates need not be.
constexpr int dyadic_grid = -50;

// A cp edge A -> B with B - A = 2^-q (a, b), (a, b) an integer direction: half of the time a
// short one, (1, 0), (2, 1), ... with q = 1..3, half of the time a = 2^18..2^20, b likewise,
// with q = 20, whose products of coordinates do not fit a double (no free exactness for Float).
struct DyadicEdge {
  Point2 a;
  Point2 b;
  int q;
};

DyadicEdge dyadic_edge(Rng& rng) {
  static constexpr std::array<std::array<int, 2>, 9> short_directions{
      {{1, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 2}, {3, 1}, {1, 3}, {3, 2}, {2, 3}}};
  double a = 0.0, b = 0.0;
  int q = 20;
  if (rng.chance(0.5)) {
    const auto& dir = short_directions[rng.index(short_directions.size())];
    a = dir[0], b = dir[1];
    q = (a <= 1.0 && b <= 1.0 ? 1 : 2) + static_cast<int>(rng.integer(0, 1));
  } else {
    a = static_cast<double>(rng.integer(1 << 18, 1 << 20));
    b = static_cast<double>(rng.integer(1 << 18, 1 << 20));
  }
  const Vector2 step{std::ldexp(a * rng.sign(), -q), std::ldexp(b * rng.sign(), -q)};
  const Point2 start = snap(random_point(rng, 0.5), dyadic_grid);
  return {start, start + step, q};
}

// The point A + s (B - A); exact for the s used here: s = k / 2^m with k (a, b) below 2^41
// and m <= 20, |s| <= 3/2, so s (B - A) is a multiple of 2^-50 and A + s (B - A) below 4 m.
Point2 along(const DyadicEdge& e, double s) { return e.a + s * (e.b - e.a); }

// Snapped points A + s (B - A) + t * left(B - A), kept when on the `side` of line A -> B.
void add_points_beside(Rng& rng, const DyadicEdge& e, double s_lo, double s_hi, double t_lo,
                       double t_hi, Sign side, Polygon& points) {
  const auto count = rng.integer(1, 6);
  for (std::int64_t k = 0; k < count; ++k) {
    const double t = rng.uniform(t_lo, t_hi) * (side == Sign::positive ? 1.0 : -1.0);
    const Point2 x = snap(along(e, rng.uniform(s_lo, s_hi)) + t * left_normal(e.b - e.a), dyadic_grid);
    if (orient(e.a, e.b, x) == side) points.push_back(x);
  }
}

// A dyadic polygon with the edge A -> B (all other vertices strictly on its left).
Polygon polygon_on_edge(Rng& rng, const DyadicEdge& e) {
  Polygon points{e.a, e.b};
  add_points_beside(rng, e, 0.05, 0.95, 0.1, 1.2, Sign::positive, points);
  Polygon cp = convex_hull(std::move(points));
  if (valid(cp) && !has_edge(cp, e.a, e.b)) generator_bug("cp lost its edge A -> B");
  return cp;
}

std::optional<PolygonPair> vertex_on_edge_pair(Rng& rng) {
  const DyadicEdge e = dyadic_edge(rng);
  Polygon cp = polygon_on_edge(rng, e);
  const int m = static_cast<int>(rng.integer(1, 20));
  const Point2 v = along(e, std::ldexp(static_cast<double>(rng.integer(1, (std::int64_t{1} << m) - 1)), -m));
  if (orient(e.a, e.b, v) != Sign::zero) generator_bug("V is not on the line A -> B");
  const Vector2 u = unit(e.b - e.a);
  const auto variant = rng.integer(0, 3);
  Point2 apex = v;
  if (variant >= 2) {
    // V moved by 2^-j times the edge's left normal 2^-q (-b, a): a multiple of 2^(-q - j)
    // >= 2^-50, so on the grid and exact. (offset_1e6's snapping to 2^-33 rounds the smaller
    // shifts to 0 or 2^-33.)
    const int j = static_cast<int>(rng.integer(24, 50 - e.q));
    const double shift = std::ldexp(variant == 2 ? 1.0 : -1.0, -j);
    apex = v + shift * left_normal(e.b - e.a);
    const Sign expected = variant == 2 ? Sign::positive : Sign::negative;
    if (orient(e.a, e.b, apex) != expected) generator_bug("shifted V is on the wrong side");
  }
  Polygon points{apex};
  const auto count = rng.integer(2, 6);
  for (std::int64_t k = 0; k < count; ++k) {
    const Vector2 dir = variant == 1 ? turned_in(rng, u, 0.27) : rightward(rng, u);
    const Point2 x = snap(apex + rng.uniform(0.2, 1.0) * dir, dyadic_grid);
    if (variant == 1 || orient(e.a, e.b, x) == Sign::negative) points.push_back(x);
  }
  Polygon tp = convex_hull(std::move(points));
  if (!contains_vertex(tp, apex)) return std::nullopt;
  return pair_if_valid(std::move(cp), std::move(tp));
}

Polygon snapped_convex(Rng& rng, const Point2& centre, int grid_exponent) {
  Polygon points = random_convex(rng, centre, 10, 1.0);
  for (Point2& p : points) p = snap(p, grid_exponent);
  return convex_hull(std::move(points));
}

std::optional<PolygonPair> vertex_on_vertex_pair(Rng& rng) {
  Polygon cp = snapped_convex(rng, snap(random_point(rng, 0.5), dyadic_grid), dyadic_grid);
  if (!valid(cp)) return std::nullopt;
  const std::size_t n = cp.size(), i = rng.index(n);
  const Point2 c = cp[i], prev = cp[(i + n - 1) % n], next = cp[(i + 1) % n];
  Polygon tp;
  if (rng.chance(0.5)) {
    tp = rng.chance(0.5) ? outside_at(rng, c, c, next, dyadic_grid)
                         : outside_at(rng, c, prev, c, dyadic_grid);
  } else {
    Polygon points{c};
    const Vector2 u = unit(next - c);
    const auto count = rng.integer(2, 6);
    for (std::int64_t k = 0; k < count; ++k) {
      const Vector2 direction = turned_in(rng, u, 0.5);
      points.push_back(snap(c + rng.uniform(0.2, 1.0) * direction, dyadic_grid));
    }
    tp = convex_hull(std::move(points));
  }
  if (!contains_vertex(tp, c)) return std::nullopt;
  return pair_if_valid(std::move(cp), std::move(tp));
}

std::optional<PolygonPair> edge_on_edge_pair(Rng& rng) {
  const DyadicEdge e = dyadic_edge(rng);
  Polygon cp = polygon_on_edge(rng, e);
  // tp's edge covers [s0, s1] of cp's edge parameter, s = k / 2^m in [-1/2, 3/2].
  const int m = static_cast<int>(rng.integer(0, 3));
  const std::int64_t q = std::int64_t{1} << m;
  std::int64_t k0 = rng.integer(-q / 2, q + q / 2 - 1);
  std::int64_t k1 = rng.integer(k0 + 1, q + q / 2);
  if (rng.chance(0.2)) {  // an endpoint shared with cp's edge
    const std::int64_t len = k1 - k0;
    if (rng.chance(0.5)) k0 = q, k1 = q + len;
    else k1 = 0, k0 = -len;
  }
  const double s0 = std::ldexp(static_cast<double>(k0), -m), s1 = std::ldexp(static_cast<double>(k1), -m);
  const Point2 p0 = along(e, s0), p1 = along(e, s1);
  if (orient(e.a, e.b, p0) != Sign::zero || orient(e.a, e.b, p1) != Sign::zero) {
    generator_bug("tp's edge is not on cp's edge line");
  }
  const bool outside = rng.chance(0.65);
  const double margin = 0.1 * (s1 - s0);
  Polygon points{p0, p1};
  add_points_beside(rng, e, s0 + margin, s1 - margin, outside ? 0.1 : 0.05, outside ? 1.0 : 0.6,
                    outside ? Sign::negative : Sign::positive, points);
  Polygon tp = convex_hull(std::move(points));
  if (valid(tp) && !(outside ? has_edge(tp, p1, p0) : has_edge(tp, p0, p1))) {
    generator_bug("tp lost its collinear edge");
  }
  return pair_if_valid(std::move(cp), std::move(tp));
}

// ---- lattice ------------------------------------------------------------------------------

constexpr double lattice_step = 0.125;  // m, 2^-3

Point2 lattice_point(std::int64_t i, std::int64_t j) {
  return {static_cast<double>(i) * lattice_step, static_cast<double>(j) * lattice_step};
}

Polygon lattice_polygon(Rng& rng, std::int64_t i0, std::int64_t j0) {
  Polygon points;
  const auto count = rng.integer(4, 10);
  for (std::int64_t k = 0; k < count; ++k) {
    const std::int64_t j = j0 + rng.integer(0, 8);
    points.push_back(lattice_point(i0 + rng.integer(0, 8), j));
  }
  return convex_hull(std::move(points));
}

std::optional<PolygonPair> lattice_touch_pair(Rng& rng) {
  Polygon cp = lattice_polygon(rng, 0, 0);
  if (!valid(cp)) return std::nullopt;
  if (rng.chance(0.5)) {
    const std::int64_t j0 = rng.integer(-6, 6);
    Polygon tp = lattice_polygon(rng, rng.integer(-6, 6), j0);
    return pair_if_valid(std::move(cp), std::move(tp));
  }
  // tp in the closed outer half-plane of cp's edge P -> Q, through a lattice point T of PQ.
  const std::size_t k = rng.index(cp.size());
  const Point2 p = cp[k], q = cp[(k + 1) % cp.size()];
  const auto steps = std::gcd(static_cast<std::int64_t>(std::fabs(q.x - p.x) / lattice_step),
                              static_cast<std::int64_t>(std::fabs(q.y - p.y) / lattice_step));
  const double l = static_cast<double>(rng.integer(0, steps)) / static_cast<double>(steps);
  const Point2 t = p + l * (q - p);
  if (orient(p, q, t) != Sign::zero) generator_bug("T is not on cp's edge");
  Polygon points{t};
  const auto count = rng.integer(2, 7);
  for (std::int64_t attempt = 0; attempt < 64 && std::ssize(points) <= count; ++attempt) {
    const std::int64_t j = rng.integer(-8, 16);
    const Point2 x = lattice_point(rng.integer(-8, 16), j);
    if (orient(p, q, x) != Sign::positive) points.push_back(x);
  }
  return pair_if_valid(std::move(cp), convex_hull(std::move(points)));
}

// A right triangle with legs along the axes whose sides are a Pythagorean triple (a, b, c)
// times s = 2^-4 m, and a tp with an edge through cp's incentre: there the distance lines of
// cp's three edges meet exactly (the incentre is the lattice point (r s, r s) from the right
// angle, r = (a + b - c) / 2), and dividing by the hypotenuse c s rounds. A tp edge through it
// carries an IP edge whose envelope has a three-line tie that rounding can break either way.
std::optional<PolygonPair> incentre_pair(Rng& rng, std::string& recipe) {
  static constexpr std::array<std::array<std::int64_t, 3>, 4> triples{{{3, 4, 5}, {5, 12, 13}, {8, 15, 17}, {7, 24, 25}}};
  constexpr double s = 0x1p-4;
  const auto& triple = triples[rng.index(triples.size())];
  const bool swap_legs = rng.chance(0.5);
  const double sx = rng.sign();
  const double sy = rng.sign();
  const double a = static_cast<double>(swap_legs ? triple[1] : triple[0]);
  const double b = static_cast<double>(swap_legs ? triple[0] : triple[1]);
  const double r = static_cast<double>((triple[0] + triple[1] - triple[2]) / 2);
  Polygon cp = convex_hull({{0, 0}, {sx * a * s, 0}, {0, sy * b * s}});
  const Point2 incentre{sx * r * s, sy * r * s};
  const std::int64_t p = rng.integer(-3, 3);
  const std::int64_t q = rng.integer(-3, 3);
  if (p == 0 && q == 0) return std::nullopt;
  const Vector2 d{static_cast<double>(p) * s, static_cast<double>(q) * s};
  const double k0 = static_cast<double>(rng.integer(1, 3));
  const double k1 = static_cast<double>(rng.integer(1, 3));
  const Point2 t0 = incentre + k0 * d, t1 = incentre + -k1 * d;
  Polygon points{t0, t1};
  const auto extra = rng.integer(1, 4);
  for (std::int64_t attempt = 0; attempt < 64 && std::ssize(points) < extra + 2; ++attempt) {
    const std::int64_t i = rng.integer(-16, 16);
    const Point2 x = incentre + Vector2{static_cast<double>(i) * s, static_cast<double>(rng.integer(-16, 16)) * s};
    if (orient(t0, t1, x) == Sign::positive) points.push_back(x);
  }
  if (orient(t0, t1, incentre) != Sign::zero) generator_bug("the tp edge misses the incentre");
  Polygon tp = convex_hull(std::move(points));
  if (!has_edge(tp, t0, t1)) generator_bug("t0 t1 is not a tp edge");
  recipe = format("cp the (%d, %d, %d) right triangle x 2^-4, tp edge through its incentre along (%d, %d)",
                  static_cast<int>(a), static_cast<int>(b), static_cast<int>(triple[2]), static_cast<int>(p),
                  static_cast<int>(q));
  return pair_if_valid(std::move(cp), std::move(tp));
}

std::optional<PolygonPair> lattice_concurrent_pair(Rng& rng) {
  std::string recipe;
  std::optional<PolygonPair> pair;
  if (rng.chance(0.5)) {
    pair = incentre_pair(rng, recipe);
  } else {
    Polygon cp = lattice_polygon(rng, 0, 0);
    const std::int64_t i0 = rng.integer(-4, 4);
    const std::int64_t j0 = rng.integer(-4, 4);
    pair = pair_if_valid(std::move(cp), lattice_polygon(rng, i0, j0));
    recipe = format("two lattice hulls, tp at (%d, %d) steps", static_cast<int>(i0), static_cast<int>(j0));
  }
  if (pair) pair->recipe = recipe;
  return pair;
}

// ---- exact incidences on generic lines ------------------------------------------------------

// Grid of the polygons of near_parallel_ulp and nested (m). Their random polygons lie within
// 1.1 m of the origin, so on this grid B - A is a multiple of 2^-30 below 4 (exact), and for
// s = j / 2^m, m <= 20, s (B - A) is a multiple of 2^-50 below 4 and A + s (B - A) one below
// 2: at most 52 significant bits each, so the point is computed exactly and lies on the line
// A -> B, whose slope is a generic 31-bit fraction.
constexpr int incidence_grid = -30;

Point2 exactly_on_line(const Point2& a, const Point2& b, std::int64_t j, int m) {
  const Point2 p = a + std::ldexp(static_cast<double>(j), -m) * (b - a);
  if (orient(a, b, p) != Sign::zero) generator_bug("a point A + j / 2^m (B - A) is off the line A -> B");
  return p;
}

// p with one coordinate moved by one ulp to the `side` of the line a -> b (decided exactly):
// the x coordinate when the line is steeper than 45°, else y, so that the move is mostly
// across the line. Moving x by e changes (b - a) x (p - a) by -(b.y - a.y) e, nonzero, so one
// of the two directions gives each side.
Point2 one_ulp_to(const Point2& a, const Point2& b, const Point2& p, Sign side) {
  const bool move_x = std::fabs(b.y - a.y) >= std::fabs(b.x - a.x);
  for (const double towards : {HUGE_VAL, -HUGE_VAL}) {
    Point2 q = p;
    double& coordinate = move_x ? q.x : q.y;
    coordinate = std::nextafter(coordinate, towards);
    if (orient(a, b, q) == side) return q;
  }
  generator_bug("no one-ulp move reaches the side");
}

bool strictly_inside(const Polygon& poly, const Point2& x) {
  for (std::size_t k = 0; k < poly.size(); ++k) {
    if (orient(poly[k], poly[(k + 1) % poly.size()], x) != Sign::positive) return false;
  }
  return true;
}

std::optional<PolygonPair> near_parallel_ulp_pair(Rng& rng) {
  const Point2 centre = random_point(rng, 0.5);
  Polygon cp = snapped_convex(rng, centre, incidence_grid);
  if (!valid(cp)) return std::nullopt;
  const std::size_t k = long_edge(rng, cp);
  if (length(cp[(k + 1) % cp.size()] - cp[k]) < 0.1) return std::nullopt;
  const Point2 a = cp[k], b = cp[(k + 1) % cp.size()];
  // The on-line point in the middle half of the edge.
  const int m = static_cast<int>(rng.integer(2, 20));
  const std::int64_t quarter = std::int64_t{1} << (m - 2);
  const Point2 on_line = exactly_on_line(a, b, rng.integer(quarter, 3 * quarter), m);
  const auto variant = rng.integer(0, 2);
  static constexpr std::array<const char*, 3> variant_names{
      "P0 on the cp edge line", "P0 one ulp inside the cp edge line", "P0 one ulp outside the cp edge line"};
  const Point2 p0 =
      variant == 0 ? on_line : one_ulp_to(a, b, on_line, variant == 1 ? Sign::positive : Sign::negative);
  // tp's edge P0 -> P1 runs against A -> B turned by `angle`: for angle > 0 its far end is
  // outside cp's edge line, for angle < 0 inside; tp lies on its left, cp's outside.
  const double magnitude = rng.log_uniform(1e-13, 1e-11);
  const double angle = rng.sign() * magnitude;
  const Vector2 d = rotate(-unit(b - a), angle / 2.0);
  const double tp_length = rng.uniform(0.3, 1.2);
  Polygon points{p0, p0 + tp_length * d};
  const auto extra = rng.integer(1, 5);
  for (std::int64_t i = 0; i < extra; ++i) {
    const double along_d = rng.uniform(0.1, 0.9) * tp_length;
    points.push_back(p0 + along_d * d + rng.uniform(0.1, 0.8) * left_normal(d));
  }
  Polygon tp = convex_hull(std::move(points));
  if (!contains_vertex(tp, p0)) generator_bug("P0 is not a vertex of tp");
  std::optional<PolygonPair> pair = pair_if_valid(std::move(cp), std::move(tp));
  if (pair) {
    pair->recipe = format("%s, angle %.3g rad %s", variant_names[static_cast<std::size_t>(variant)], angle,
                          angle > 0.0 ? "(turned away from cp)" : "(turned into cp)");
  }
  return pair;
}

// A point strictly inside `outer` (checked exactly; nullopt when rounding put it elsewhere):
// on the segment from the vertex mean to a random boundary point.
std::optional<Point2> interior_point(Rng& rng, const Polygon& outer) {
  const Point2 c = vertex_mean(outer);
  const std::size_t k = rng.index(outer.size());
  const Point2 q = outer[k] + rng.unit() * (outer[(k + 1) % outer.size()] - outer[k]);
  const Point2 x = c + rng.uniform(0.05, 0.95) * (q - c);
  if (!strictly_inside(outer, x)) return std::nullopt;
  return x;
}

enum class Nesting : std::int64_t { strictly, vertex_on_edge, along_edge, shared_vertex };

std::optional<PolygonPair> nested_pair(Rng& rng, Nesting nesting) {
  static constexpr std::array<const char*, 4> variant_names{
      "strictly", "touching: a vertex on an edge", "touching: along an edge", "touching: a shared vertex"};
  const auto variant = static_cast<std::int64_t>(nesting);
  const Point2 centre = random_point(rng, 0.5);
  Polygon outer = snapped_convex(rng, centre, incidence_grid);
  if (!valid(outer)) return std::nullopt;
  const std::size_t k = rng.index(outer.size());
  const Point2 a = outer[k], b = outer[(k + 1) % outer.size()];
  Polygon boundary_points;
  if (variant == 1 || variant == 2) {
    const int m = static_cast<int>(rng.integer(variant == 1 ? 1 : 2, 20));
    const std::int64_t last = (std::int64_t{1} << m) - 1;
    const std::int64_t j0 = rng.integer(1, variant == 1 ? last : last - 1);
    boundary_points.push_back(exactly_on_line(a, b, j0, m));
    if (variant == 2) boundary_points.push_back(exactly_on_line(a, b, rng.integer(j0 + 1, last), m));
  } else if (variant == 3) {
    boundary_points.push_back(a);
  }
  Polygon points = boundary_points;
  const auto count = rng.integer(3, 8);
  for (std::int64_t i = 0; i < count; ++i) {
    if (const std::optional<Point2> x = interior_point(rng, outer)) points.push_back(*x);
  }
  // The boundary points are on the line A -> B and every other point strictly left of it, so
  // they are extreme: vertices of the inner hull.
  Polygon inner = convex_hull(std::move(points));
  for (const Point2& p : boundary_points) {
    if (valid(inner) && !contains_vertex(inner, p)) generator_bug("nested: lost a boundary vertex");
  }
  const bool inner_is_tp = rng.chance(0.5);
  std::optional<PolygonPair> pair = inner_is_tp ? pair_if_valid(std::move(outer), std::move(inner))
                                                : pair_if_valid(std::move(inner), std::move(outer));
  if (pair) {
    pair->recipe = std::string(inner_is_tp ? "tp inside cp, " : "cp inside tp, ") +
                   variant_names[static_cast<std::size_t>(variant)];
  }
  return pair;
}

std::optional<PolygonPair> nested_pair(Rng& rng) {
  const auto variant = rng.integer(0, 3);
  return nested_pair(rng, static_cast<Nesting>(variant));
}

// The polygon with vertex i's x (or y) moved by one ulp, if it stays strictly convex with the
// same vertices (decided by the exact hull).
std::optional<Polygon> moved_by_one_ulp(const Polygon& poly, std::size_t i, bool move_x, double towards) {
  Polygon moved = poly;
  double& coordinate = move_x ? moved[i].x : moved[i].y;
  coordinate = std::nextafter(coordinate, towards);
  const Point2 v = moved[i];
  Polygon hull = convex_hull(std::move(moved));
  if (hull.size() != poly.size() || !contains_vertex(hull, v)) return std::nullopt;
  return hull;
}

std::optional<PolygonPair> identical_pair(Rng& rng) {
  Polygon cp;
  std::string shape = "ordinary";
  if (rng.chance(0.6)) {
    const Point2 centre = random_point(rng, 0.5);
    cp = random_convex(rng, centre, 10, 1.0);
  } else {
    const Sliver s = random_sliver(rng, false);
    cp = s.polygon;
    shape = describe(s);
  }
  if (!valid(cp)) return std::nullopt;
  if (rng.chance(0.5)) {
    Polygon tp = cp;
    std::optional<PolygonPair> pair = pair_if_valid(std::move(cp), std::move(tp));
    if (pair) pair->recipe = "cp " + shape + ", tp the same vertices";
    return pair;
  }
  const std::size_t i = rng.index(cp.size());
  const bool move_x = rng.chance(0.5);
  const double towards = rng.sign() * HUGE_VAL;
  std::optional<Polygon> tp = moved_by_one_ulp(cp, i, move_x, towards);
  if (!tp) return std::nullopt;
  const bool swap = rng.chance(0.5);
  std::optional<PolygonPair> pair = swap ? pair_if_valid(std::move(*tp), std::move(cp))
                                         : pair_if_valid(std::move(cp), std::move(*tp));
  if (pair) {
    pair->recipe = format("%s %s, %s the same but one vertex's %s moved one ulp %s", swap ? "tp" : "cp",
                          shape.c_str(), swap ? "cp" : "tp", move_x ? "x" : "y", towards > 0.0 ? "up" : "down");
  }
  return pair;
}

// ---- far from the origin --------------------------------------------------------------------

constexpr int offset_grid = -33;
constexpr Vector2 far_offset{1.0e6, -1.0e6};

std::optional<PolygonPair> generate_once(Family family, Rng& rng);

std::optional<PolygonPair> offset_pair(Rng& rng) {
  static constexpr std::array<Family, 9> bases{
      Family::random,         Family::short_edges,      Family::wedge_5deg,
      Family::wedge_0_5deg,   Family::near_parallel,    Family::vertex_on_edge,
      Family::vertex_on_vertex, Family::edge_on_edge,   Family::lattice_touch};
  const std::optional<PolygonPair> base = generate_once(bases[rng.index(bases.size())], rng);
  if (!base) return std::nullopt;
  const std::optional<PolygonPair> snapped = snap_to_grid(*base, offset_grid);
  if (!snapped) return std::nullopt;
  std::optional<PolygonPair> far = translate_exactly(*snapped, far_offset);
  if (!far) generator_bug("the translation by (1e6, -1e6) was not exact");
  return far;
}

// ---- meta families ------------------------------------------------------------------------

// The families a meta family draws its base pair from.
constexpr std::array<Family, 15> plain_families{
    Family::random,           Family::short_edges,  Family::wedge_5deg,     Family::wedge_0_5deg,
    Family::near_parallel,    Family::vertex_on_edge, Family::vertex_on_vertex, Family::edge_on_edge,
    Family::lattice_touch,    Family::sliver,       Family::wedge_0_1deg,   Family::tiny_edges,
    Family::near_parallel_ulp, Family::nested,      Family::identical};

// A base pair named by its own (family, seed, index), so a recipe that quotes the base's
// recipe regenerates it.
PolygonPair base_pair(Rng& rng) {
  const Family family = plain_families[rng.index(plain_families.size())];
  return generate_pair(family, rng.bits(), 0);
}

double largest_coordinate(const PolygonPair& pair) {
  double best = 0.0;
  for (const Polygon* poly : {&pair.cp, &pair.tp}) {
    for (const Point2& p : *poly) best = std::max({best, std::fabs(p.x), std::fabs(p.y)});
  }
  return best;
}

std::optional<PolygonPair> far_offset_pair(Rng& rng) {
  const PolygonPair base = base_pair(rng);
  const double x = rng.log_uniform(1e6, 1e9);
  const double x_sign = rng.sign();
  const double y = rng.log_uniform(1e6, 1e9);
  const double y_sign = rng.sign();
  // 2^e > |offset| + |base coordinates| + 1 (the 1 m covers the rounding of the snaps), and
  // the grid 2^(e - 53): see the header.
  const double bound = std::max(x, y) + largest_coordinate(base) + 1.0;
  int e = 0;
  while (std::ldexp(1.0, e) <= bound) ++e;
  const int grid = e - 53;
  const Vector2 offset{snap(x_sign * x, grid), snap(y_sign * y, grid)};
  const std::optional<PolygonPair> snapped = snap_to_grid(base, grid);
  if (!snapped) return std::nullopt;
  std::optional<PolygonPair> far = translate_exactly(*snapped, offset);
  if (!far) generator_bug("the translation by " + format("(%.17g, %.17g)", offset.x, offset.y) + " was not exact");
  far->recipe = format("offset (%.3g, %.3g), grid 2^%d, base ", offset.x, offset.y, grid) + base.recipe;
  return far;
}

// `base` turned as a whole by a random rational rotation about a random grid centre (see the
// header's `rotated`), each polygon re-hulled; the recipe names the rotation, then the base.
std::optional<PolygonPair> rotated_randomly(Rng& rng, const PolygonPair& base) {
  const double t = std::ldexp(static_cast<double>(rng.integer(-(1 << 16), 1 << 16)), -16);
  const bool half_turn = rng.chance(0.5);
  const double centre_x = std::ldexp(static_cast<double>(rng.integer(-256, 256)), -8);
  const Point2 centre{centre_x, std::ldexp(static_cast<double>(rng.integer(-256, 256)), -8)};
  const auto turned = [&](const Polygon& poly) {
    Polygon out;
    for (const Point2& p : poly) {
      const Vector2 r = rotate(p - centre, t);
      out.push_back(centre + (half_turn ? -r : r));
    }
    return convex_hull(std::move(out));
  };
  std::optional<PolygonPair> pair = pair_if_valid(turned(base.cp), turned(base.tp));
  if (pair) {
    pair->recipe = format("t %.17g%s, centre (%.17g, %.17g), base ", t, half_turn ? " plus a half turn" : "",
                          centre.x, centre.y) + base.recipe;
  }
  return pair;
}

std::optional<PolygonPair> rotated_pair(Rng& rng) { return rotated_randomly(rng, base_pair(rng)); }

// Nested polygons touching along an edge (3/4) or at an inner vertex on an outer edge, the
// inner one as cp or tp, turned by a rational rotation: the inner edge lies along the outer
// one to within rounding, so crossings of those two edges' lines are as ill-conditioned as
// crossings get, and one of them sits on an inner vertex.
std::optional<PolygonPair> nested_rotated_pair(Rng& rng) {
  const Nesting nesting = rng.chance(0.75) ? Nesting::along_edge : Nesting::vertex_on_edge;
  const std::optional<PolygonPair> base = nested_pair(rng, nesting);
  if (!base) return std::nullopt;
  return rotated_randomly(rng, *base);
}

std::optional<PolygonPair> generate_once(Family family, Rng& rng) {
  switch (family) {
    case Family::random: return random_pair(rng);
    case Family::short_edges: return short_edges_pair(rng);
    case Family::wedge_5deg: return wedge_pair(rng, tan_half_5deg);
    case Family::wedge_0_5deg: return wedge_pair(rng, tan_half_0_5deg);
    case Family::near_parallel: return near_parallel_pair(rng);
    case Family::vertex_on_edge: return vertex_on_edge_pair(rng);
    case Family::vertex_on_vertex: return vertex_on_vertex_pair(rng);
    case Family::edge_on_edge: return edge_on_edge_pair(rng);
    case Family::offset_1e6: return offset_pair(rng);
    case Family::lattice_touch: return lattice_touch_pair(rng);
    case Family::sliver: return sliver_pair(rng);
    case Family::wedge_0_1deg: return fine_wedge_pair(rng);
    case Family::tiny_edges: return tiny_edges_pair(rng);
    case Family::near_parallel_ulp: return near_parallel_ulp_pair(rng);
    case Family::nested: return nested_pair(rng);
    case Family::identical: return identical_pair(rng);
    case Family::offset_1e9: return far_offset_pair(rng);
    case Family::rotated: return rotated_pair(rng);
    case Family::lattice_concurrent: return lattice_concurrent_pair(rng);
    case Family::nested_rotated: return nested_rotated_pair(rng);
  }
  generator_bug("unknown family");
}

// Starts a polygon at a random vertex (the hull always starts at the lowest-leftmost one).
void rotate_start(Rng& rng, Polygon& poly) {
  std::rotate(poly.begin(), poly.begin() + static_cast<std::ptrdiff_t>(rng.index(poly.size())), poly.end());
}

bool exact_sum(double a, double b, double& sum) {
  // Knuth's TwoSum: `error` is the exact rounding error of a + b.
  sum = a + b;
  const double b_virtual = sum - a;
  const double error = (a - (sum - b_virtual)) + (b - b_virtual);
  return error == 0.0 && std::isfinite(sum);
}

}  // namespace

std::string_view to_string(Family family) {
  switch (family) {
    case Family::random: return "random";
    case Family::short_edges: return "short_edges";
    case Family::wedge_5deg: return "wedge_5deg";
    case Family::wedge_0_5deg: return "wedge_0_5deg";
    case Family::near_parallel: return "near_parallel";
    case Family::vertex_on_edge: return "vertex_on_edge";
    case Family::vertex_on_vertex: return "vertex_on_vertex";
    case Family::edge_on_edge: return "edge_on_edge";
    case Family::offset_1e6: return "offset_1e6";
    case Family::lattice_touch: return "lattice_touch";
    case Family::sliver: return "sliver";
    case Family::wedge_0_1deg: return "wedge_0_1deg";
    case Family::tiny_edges: return "tiny_edges";
    case Family::near_parallel_ulp: return "near_parallel_ulp";
    case Family::nested: return "nested";
    case Family::identical: return "identical";
    case Family::offset_1e9: return "offset_1e9";
    case Family::rotated: return "rotated";
    case Family::lattice_concurrent: return "lattice_concurrent";
    case Family::nested_rotated: return "nested_rotated";
  }
  return "?";
}

std::optional<Family> parse_family(std::string_view name) {
  for (Family f : all_families) {
    if (to_string(f) == name) return f;
  }
  return std::nullopt;
}

PolygonPair generate_pair(Family family, std::uint64_t seed, std::uint64_t index) {
  Rng rng(mix(mix(seed) ^ mix(index) ^ (static_cast<std::uint64_t>(family) << 56)));
  for (int attempt = 0; attempt < 1000; ++attempt) {
    if (std::optional<PolygonPair> pair = generate_once(family, rng)) {
      rotate_start(rng, pair->cp);
      rotate_start(rng, pair->tp);
      pair->recipe = std::string(to_string(family)) + " seed " + std::to_string(seed) + " index " +
                     std::to_string(index) + (pair->recipe.empty() ? "" : ": " + pair->recipe);
      return std::move(*pair);
    }
  }
  generator_bug("no valid pair of family " + std::string(to_string(family)) + " in 1000 attempts");
}

std::vector<Point2> convex_hull(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  // Andrew's monotone chain: lower hull left to right, upper hull right to left, keeping only
  // strict left turns.
  std::vector<Point2> hull;
  const auto add = [&](const Point2& p, std::size_t floor) {
    while (hull.size() >= floor + 2 && orient(hull[hull.size() - 2], hull.back(), p) != Sign::positive) {
      hull.pop_back();
    }
    hull.push_back(p);
  };
  for (const Point2& p : points) add(p, 0);
  const std::size_t lower = hull.size() - 1;
  for (auto it = points.rbegin() + 1; it != points.rend(); ++it) add(*it, lower);
  hull.pop_back();  // the first point again
  return hull;
}

std::optional<PolygonPair> snap_to_grid(const PolygonPair& pair, int grid_exponent) {
  const auto snapped = [&](const Polygon& poly) {
    Polygon out;
    for (const Point2& p : poly) out.push_back(snap(p, grid_exponent));
    return convex_hull(std::move(out));
  };
  return pair_if_valid(snapped(pair.cp), snapped(pair.tp));
}

std::optional<PolygonPair> translate_exactly(const PolygonPair& pair, Vector2 offset) {
  PolygonPair out = pair;
  for (Polygon* poly : {&out.cp, &out.tp}) {
    for (Point2& p : *poly) {
      if (!exact_sum(p.x, offset.x, p.x) || !exact_sum(p.y, offset.y, p.y)) return std::nullopt;
    }
  }
  return out;
}

}  // namespace rockcontact::robustness
