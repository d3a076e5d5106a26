#include "pair_generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "rockcontact/kernel/number_policy.hpp"
#include "rockcontact/kernel/predicates.hpp"

namespace rockcontact::robustness {
namespace {

using kernel::Sign;
using Polygon = std::vector<Point2>;

// Exact orientation (the kernel's filtered predicate, exact by contract and checked against
// GMP in kernel/tests/predicates_test.cpp).
Sign orient(const Point2& p, const Point2& q, const Point2& r) {
  return kernel::orientation<kernel::Filtered>(p, q, r);
}

// splitmix64's finaliser (Steele, Lea, Flood 2014): decorrelates the engine seeds of
// neighbouring (seed, family, index) triples.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Random numbers with distributions written out here: std::uniform_real_distribution and
// friends are implementation-defined, the raw mt19937_64 sequence is not.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // Uniform on [0, 1): the top 53 bits of one draw, scaled exactly.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  double sign() { return chance(0.5) ? 1.0 : -1.0; }

  // Uniform on {lo, ..., hi}, by rejection of the draws below 2^64 mod range (no modulo bias).
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    const std::uint64_t range = static_cast<std::uint64_t>(hi - lo) + 1;
    const std::uint64_t threshold = (0 - range) % range;
    std::uint64_t draw = engine_();
    while (draw < threshold) draw = engine_();
    return lo + static_cast<std::int64_t>(draw % range);
  }
  std::size_t index(std::size_t size) {
    return static_cast<std::size_t>(integer(0, static_cast<std::int64_t>(size) - 1));
  }

  // (1 + u) 2^e with e uniform in [lo_exponent, hi_exponent]: log-uniform to within a factor
  // of two per octave; ldexp scales exactly.
  double octaves(int lo_exponent, int hi_exponent) {
    return std::ldexp(1.0 + unit(), static_cast<int>(integer(lo_exponent, hi_exponent)));
  }

 private:
  std::mt19937_64 engine_;
};

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
    Point2 x = c + rng.uniform(0.2, 1.0) * rightward(rng, u);
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
    return pair_if_valid(cp, place_at_gap(cp, local, u, rng.uniform(-0.02, 0.02), lateral_offset(rng)));
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
  Polygon tp = place_at_gap(cp, local, random_direction(rng), rng.uniform(-0.02, 0.005), lateral_offset(rng));
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

std::optional<PolygonPair> near_parallel_pair(Rng& rng) {
  Polygon cp = random_convex(rng, random_point(rng, 0.5), 10, 1.0);
  if (!valid(cp)) return std::nullopt;
  std::size_t k = rng.index(cp.size());
  const auto edge = [&](std::size_t i) { return cp[(i + 1) % cp.size()] - cp[i]; };
  if (length(edge(k)) < 0.1) {
    for (std::size_t i = 0; i < cp.size(); ++i) {
      if (length(edge(i)) > length(edge(k))) k = i;
    }
  }
  const Vector2 e = edge(k);
  const Vector2 outward = right_normal(unit(e));
  // tp's edge P0 -> P1 runs against e, turned by ~angle; tp lies on its left, outside cp.
  const double angle = rng.sign() * rng.octaves(-39, -21);
  const Vector2 d = rotate(-unit(e), angle / 2.0);
  const double offset = rng.chance(0.1) ? 0.0 : rng.sign() * rng.octaves(-50, -20);
  const Point2 p0 = cp[k] + rng.uniform(0.2, 1.5) * e + offset * outward;
  const double tp_length = rng.uniform(0.3, 1.2);
  Polygon points{p0, p0 + tp_length * d};
  const auto extra = rng.integer(1, 5);
  for (std::int64_t i = 0; i < extra; ++i) {
    points.push_back(p0 + rng.uniform(0.1, 0.9) * tp_length * d +
                     rng.uniform(0.1, 0.8) * left_normal(d));
  }
  return pair_if_valid(std::move(cp), convex_hull(std::move(points)));
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

Polygon dyadic_convex(Rng& rng, const Point2& centre) {
  Polygon points = random_convex(rng, centre, 10, 1.0);
  for (Point2& p : points) p = snap(p, dyadic_grid);
  return convex_hull(std::move(points));
}

std::optional<PolygonPair> vertex_on_vertex_pair(Rng& rng) {
  Polygon cp = dyadic_convex(rng, snap(random_point(rng, 0.5), dyadic_grid));
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
      points.push_back(snap(c + rng.uniform(0.2, 1.0) * turned_in(rng, u, 0.5), dyadic_grid));
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
    points.push_back(lattice_point(i0 + rng.integer(0, 8), j0 + rng.integer(0, 8)));
  }
  return convex_hull(std::move(points));
}

std::optional<PolygonPair> lattice_touch_pair(Rng& rng) {
  Polygon cp = lattice_polygon(rng, 0, 0);
  if (!valid(cp)) return std::nullopt;
  if (rng.chance(0.5)) {
    Polygon tp = lattice_polygon(rng, rng.integer(-6, 6), rng.integer(-6, 6));
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
    const Point2 x = lattice_point(rng.integer(-8, 16), rng.integer(-8, 16));
    if (orient(p, q, x) != Sign::positive) points.push_back(x);
  }
  return pair_if_valid(std::move(cp), convex_hull(std::move(points)));
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
