#define BOOST_TEST_MODULE kernel_cgal_reference
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/seed.hpp"

// The entrance block (seed 000 eq. 9) and the intersection polygon (Table 3) against CGAL in
// exact rational arithmetic (Simple_cartesian<mpq_class>: every double input is the rational it
// denotes, every CGAL construction is exact):
//   (a) compute_entrance_block<Filtered|Exact>(A, B) vs minkowski_sum_2(B, -A) + a0 with a0 the
//       exact mean of A's vertices (entrance_block.hpp): same shape, the verdict, the distance;
//   (b) compute_intersection_polygon + construct_points vs CGAL's regularized Boolean
//       intersection: same shape, empty exactly when the exact intersection has zero area, and
//       every IpVertex / IpEdge label true of the exact point it names.
// Shapes, not vertex lists: minkowski_sum_2 and the Boolean operations keep vertices that are
// collinear with their neighbours; they are dropped (exact orientation) before comparing with
// our strictly convex output, which is matched cyclically from any start vertex.
//
// The reference verdict is computed without the entrance block: closed convex polygons are
// disjoint exactly when an edge line of one has the whole other polygon strictly on its outer
// side (separating axis); otherwise they overlap when the exact intersection has positive
// area and touch when it has none. The exact location of a0 in the exact Minkowski polygon
// must say the same (inside = overlap, boundary = touch).
//
// Input families, each named in every failure message with its coordinates (%.17g): random
// pairs, containment, identical polygons, exactly built touching pairs with dyadic coordinates
// (vertex on edge, edge on edge, vertex on vertex) and their 2^-40 pushes in and out, a vertex
// rounded onto an edge (the rounding decides the verdict),
// near-parallel edges (1e-9 .. 1e-12 rad), 0.01 m chamfer edges, 5° and 0.5° wedges, and
// copies moved to 1e6 m (rounded) or by 2^20 (exact for the dyadic ones).

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/minkowski_sum_2.h>
#include <CGAL/mpq_class.h>
#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::IpEdge;
using rk::IpVertex;
using rk::Overlap;
using rk::Point2;

using K = CGAL::Simple_cartesian<mpq_class>;
using CPoint = K::Point_2;
using CSegment = K::Segment_2;
using CPolygon = CGAL::Polygon_2<K>;
using CPolygonWithHoles = CGAL::Polygon_with_holes_2<K>;

namespace {

using rockcontact::testing::seed_for;

constexpr double u = rockcontact::testing::unit_roundoff;

// ---------------------------------------------------------------------------------------------
// Exact helpers

// The double nearest to x, ties to even (what the Exact policy promises for each output).
double nearest(const mpq_class& x) {
  const double t = x.get_d();  // mpq_get_d truncates toward zero
  if (mpq_class(t) == x) return t;
  const double away = std::nextafter(t, sgn(x) > 0 ? HUGE_VAL : -HUGE_VAL);
  const mpq_class mid = (mpq_class(t) + mpq_class(away)) / 2;
  const int c = cmp(abs(x), abs(mid));
  if (c != 0) return c < 0 ? t : away;
  return (std::bit_cast<std::uint64_t>(t) & 1u) != 0 ? away : t;
}

CPoint lift(const Point2& p) { return {mpq_class(p.x), mpq_class(p.y)}; }

CPolygon to_cgal(const ConvexPolygon& p) {
  CPolygon out;
  for (const Point2& v : p.vertices()) out.push_back(lift(v));
  return out;
}

// -A: negating every vertex is a point reflection, so the order stays counter-clockwise.
CPolygon negated(const ConvexPolygon& p) {
  CPolygon out;
  for (const Point2& v : p.vertices()) out.push_back({mpq_class(-v.x), mpq_class(-v.y)});
  return out;
}

// The vertices of a convex CCW polygon without those collinear with their two neighbours. In
// a convex polygon a vertex inside a collinear run has both neighbours on the run's line and
// the run's ends do not, so one pass against the original neighbours removes exactly them.
std::vector<CPoint> strictly_convex(const CPolygon& p) {
  std::vector<CPoint> v(p.vertices_begin(), p.vertices_end());
  std::vector<CPoint> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const CPoint& prev = v[(i + v.size() - 1) % v.size()];
    const CPoint& next = v[(i + 1) % v.size()];
    if (CGAL::orientation(prev, v[i], next) != CGAL::COLLINEAR) out.push_back(v[i]);
  }
  return out;
}

// Separating axis on exact coordinates: some edge of one polygon has every vertex of the other
// strictly on its right (outer) side.
bool separated(const ConvexPolygon& a, const ConvexPolygon& b) {
  const auto outside_some_edge = [](const ConvexPolygon& p, const ConvexPolygon& q) {
    for (std::size_t k = 0; k < p.size(); ++k) {
      const CPoint s = lift(p[k]), t = lift(p[p.next(k)]);
      const bool all_right = std::all_of(q.vertices().begin(), q.vertices().end(), [&](const Point2& v) {
        return CGAL::orientation(s, t, lift(v)) == CGAL::RIGHT_TURN;
      });
      if (all_right) return true;
    }
    return false;
  };
  return outside_some_edge(a, b) || outside_some_edge(b, a);
}

// The exact intersection (regularized: empty for touching polygons) as a strictly convex
// vertex list, empty when its area is zero.
std::vector<CPoint> exact_intersection(const ConvexPolygon& a, const ConvexPolygon& b) {
  std::vector<CPolygonWithHoles> pieces;
  CGAL::intersection(to_cgal(a), to_cgal(b), std::back_inserter(pieces));
  BOOST_TEST_REQUIRE(pieces.size() <= 1u);  // the intersection of convex sets is convex
  if (pieces.empty()) return {};
  const CPolygon& outer = pieces.front().outer_boundary();
  BOOST_TEST_REQUIRE(!pieces.front().has_holes());
  if (outer.area() == 0) return {};
  BOOST_TEST_REQUIRE(outer.area() > 0);
  return strictly_convex(outer);
}

Overlap reference_verdict(const ConvexPolygon& a, const ConvexPolygon& b) {
  if (separated(a, b)) return Overlap::separate;
  return exact_intersection(a, b).empty() ? Overlap::touch : Overlap::overlap;
}

// ---------------------------------------------------------------------------------------------
// Input families

struct Pair {
  std::string name;
  ConvexPolygon a;
  ConvexPolygon b;
};

std::string coordinates(const ConvexPolygon& p) {
  std::ostringstream out;
  out << "[";
  char buffer[64];
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%s(%.17g, %.17g)", i == 0 ? "" : ", ", p[i].x, p[i].y);
    out << buffer;
  }
  return out.str() + "]";
}

std::string describe(const Pair& pair) {
  return pair.name + ": A = " + coordinates(pair.a) + ", B = " + coordinates(pair.b);
}

std::optional<ConvexPolygon> polygon(const std::string& name, const std::vector<Point2>& v) {
  try {
    return ConvexPolygon::make(name, v, rk::VertexOrder::normalise);
  } catch (const rk::InvalidPolygon&) {
    return std::nullopt;  // rounding (rotation, offset) made it degenerate: skip this pair
  }
}

std::vector<Point2> transformed(std::span<const Point2> v, double angle, Point2 offset) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Point2> out;
  for (const Point2& p : v) out.push_back({c * p.x - s * p.y + offset.x, s * p.x + c * p.y + offset.y});
  return out;
}

std::vector<Point2> moved(std::span<const Point2> v, Point2 offset) {
  std::vector<Point2> out;
  for (const Point2& p : v) out.push_back({p.x + offset.x, p.y + offset.y});
  return out;
}

class Families {
 public:
  explicit Families(std::uint64_t seed) : rng_(seed) {}

  std::vector<Pair> all() {
    random_pairs(60);
    touching_dyadic(16);
    rounded_touching(24);
    near_parallel(16);
    chamfer(16);
    wedges(5.0, 12);
    wedges(0.5, 12);
    return std::move(pairs_);
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  void add(const std::string& name, const std::vector<Point2>& a, const std::vector<Point2>& b) {
    auto pa = polygon(name + ".A", a), pb = polygon(name + ".B", b);
    if (pa && pb) pairs_.push_back({name, std::move(*pa), std::move(*pb)});
  }

  // The pair, and a copy moved to about 1e6 m (each coordinate rounded there).
  void add_with_far_copy(const std::string& name, const std::vector<Point2>& a, const std::vector<Point2>& b) {
    add(name, a, b);
    const Point2 far{1e6 + 0.123, -1e6 + 0.456};
    add(name + "_offset_1e6", moved(a, far), moved(b, far));
  }

  // n points on a random ellipse at sorted random angles (convex before rounding).
  std::vector<Point2> ellipse_polygon(int n, Point2 centre, double size) {
    std::vector<double> angle(n);
    for (double& x : angle) x = uniform(0.0, 6.283185307179586);
    std::sort(angle.begin(), angle.end());
    const double ra = size * uniform(0.5, 1.5), rb = size * uniform(0.5, 1.5), tilt = uniform(0.0, 3.14);
    std::vector<Point2> v;
    for (double x : angle) {
      const double px = ra * std::cos(x), py = rb * std::sin(x);
      v.push_back({centre.x + px * std::cos(tilt) - py * std::sin(tilt), centre.y + px * std::sin(tilt) + py * std::cos(tilt)});
    }
    return v;
  }

  void random_pairs(int count) {
    for (int i = 0; i < count; ++i) {
      const auto a = ellipse_polygon(integer(3, 8), {0, 0}, 1.0);
      const auto b = ellipse_polygon(integer(3, 8), {uniform(-1.8, 1.8), uniform(-1.8, 1.8)}, uniform(0.2, 1.0));
      add_with_far_copy("random_" + std::to_string(i), a, b);
    }
    for (int i = 0; i < 4; ++i) {
      const auto a = ellipse_polygon(integer(3, 8), {0, 0}, 1.0);
      std::vector<Point2> inner;  // A shrunk by half towards its vertex mean: strictly inside
      Point2 m{0, 0};
      const double vertex_count = static_cast<double>(a.size());
      for (const Point2& p : a) m = {m.x + p.x / vertex_count, m.y + p.y / vertex_count};
      for (const Point2& p : a) inner.push_back({m.x + 0.5 * (p.x - m.x), m.y + 0.5 * (p.y - m.y)});
      add("containment_" + std::to_string(i), a, inner);
      add("identical_" + std::to_string(i), a, a);
    }
  }

  // A convex polygon with coordinates on the 2^-6 grid in [-1, 1].
  std::vector<Point2> dyadic_polygon() {
    for (;;) {
      auto v = ellipse_polygon(integer(3, 7), {0, 0}, 0.7);
      for (Point2& p : v) p = {std::round(p.x * 64) / 64, std::round(p.y * 64) / 64};
      if (const auto p = polygon("dyadic", v)) return {p->vertices().begin(), p->vertices().end()};
    }
  }

  // Touching pairs built exactly: A on the 2^-6 grid, the contact point T = P + (j/8)(Q - P)
  // on edge PQ (2^-9 grid), the outward normal n = (dy, -dx) of the edge; every coordinate
  // below is exact in double. Pushing B by 2^-40 n into A makes them overlap, out of A
  // separates them. The same pairs moved by (2^20, -2^20) stay exact.
  void touching_dyadic(int count) {
    for (int i = 0; i < count; ++i) {
      const auto a = dyadic_polygon();
      const std::size_t k = static_cast<std::size_t>(integer(0, static_cast<int>(a.size()) - 1));
      const Point2 P = a[k], Q = a[(k + 1) % a.size()], R = a[(k + a.size() - 1) % a.size()];
      const Point2 d{Q.x - P.x, Q.y - P.y}, n{d.y, -d.x};
      const double s = integer(1, 7) / 8.0;
      const Point2 T{P.x + s * d.x, P.y + s * d.y};
      const auto at = [](Point2 p, Point2 v, double f) { return Point2{p.x + f * v.x, p.y + f * v.y}; };
      const auto tag = std::to_string(i);
      // Vertex of B on edge k of A; B in the outer half-plane of that edge.
      std::vector<Point2> b{T, at(at(T, n, 0.5), d, -0.25), at(at(T, n, 0.5), d, 0.25)};
      add_dyadic("touch_vertex_on_edge_" + tag, a, b);
      // Pushed by 2^-40 n (multiples of 2^-46 below 4: exact); the copy moved by 2^20 is
      // pushed by 2^-25 n instead, the smallest push that stays exact there.
      const auto push = [&](double f, Point2 offset) {
        std::vector<Point2> out;
        for (const Point2& p : b) out.push_back(at(at(p, n, f), offset, 1.0));
        return out;
      };
      const std::vector<Point2> a_far = moved(a, {0x1p20, -0x1p20});
      add("vertex_on_edge_pushed_in_2^-40_" + tag, a, push(-0x1p-40, {0, 0}));
      add("vertex_on_edge_pushed_out_2^-40_" + tag, a, push(0x1p-40, {0, 0}));
      add("vertex_on_edge_pushed_in_2^-25_offset_2^20_" + tag, a_far, push(-0x1p-25, {0x1p20, -0x1p20}));
      add("vertex_on_edge_pushed_out_2^-25_offset_2^20_" + tag, a_far, push(0x1p-25, {0x1p20, -0x1p20}));
      // Edge of B along edge k of A from s0 to s1 (in units of d), sharing a piece of positive
      // length with it, possibly running past its ends.
      const double s0 = integer(-2, 6) / 8.0, s1 = std::max(s0, 0.0) + integer(1, 4) / 8.0;
      const Point2 T0 = at(P, d, s0), T1 = at(P, d, s1);
      add_dyadic("touch_edge_on_edge_" + tag, a, {T1, T0, at(at(T0, d, 0.5 * (s1 - s0)), n, 0.5)});
      // Vertex of B on vertex P of A, B inside P's outer normal cone (spanned by the outward
      // normals m of edge k-1 and n of edge k).
      const Point2 m{P.y - R.y, R.x - P.x};
      add_dyadic("touch_vertex_on_vertex_" + tag, a, {P, at(P, m, 0.5), at(P, n, 0.5)});
    }
  }

  // A vertex of B on edge PQ of A rounded to the nearest double (decimal coordinates): whether
  // the pair touches, overlaps or separates is decided by that rounding alone.
  void rounded_touching(int count) {
    for (int i = 0; i < count; ++i) {
      const auto a = ellipse_polygon(integer(3, 7), {0.1, -0.3}, 0.9);
      const std::size_t k = static_cast<std::size_t>(integer(0, static_cast<int>(a.size()) - 1));
      const Point2 P = a[k], Q = a[(k + 1) % a.size()];
      const Point2 d{Q.x - P.x, Q.y - P.y}, n{d.y, -d.x};
      const double s = uniform(0.1, 0.9);
      const Point2 T{P.x + s * d.x, P.y + s * d.y};
      const std::vector<Point2> b{T, {T.x + 0.5 * n.x - 0.25 * d.x, T.y + 0.5 * n.y - 0.25 * d.y},
                                  {T.x + 0.5 * n.x + 0.25 * d.x, T.y + 0.5 * n.y + 0.25 * d.y}};
      add_with_far_copy("vertex_near_edge_rounded_" + std::to_string(i), a, b);
    }
  }

  void add_dyadic(const std::string& name, const std::vector<Point2>& a, const std::vector<Point2>& b) {
    add(name, a, b);
    add(name + "_offset_2^20", moved(a, {0x1p20, -0x1p20}), moved(b, {0x1p20, -0x1p20}));
  }

  // Unit square and a block above it whose bottom edge is within 1e-9..1e-12 rad of its top
  // edge, crossing it, just above or just below; also exactly on it (edge-on-edge touch).
  // Both rotated by a random angle (rounded) or kept axis-aligned.
  void near_parallel(int count) {
    const std::vector<Point2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < count; ++i) {
      const double scale = std::pow(10.0, -integer(9, 12));
      const double e0 = scale * uniform(-1, 1), e1 = i % 4 == 0 ? 0.0 : scale * uniform(-1, 1);
      const std::vector<Point2> block{{-0.2, 1 + (i % 4 == 0 ? 0.0 : e0)}, {1.2, 1 + e1}, {1.2, 2}, {-0.2, 2}};
      const double angle = i % 2 == 0 ? 0.0 : uniform(0, 6.283185307179586);
      add_with_far_copy("near_parallel_" + std::to_string(i), transformed(square, angle, {0, 0}),
                        transformed(block, angle, {0, 0}));
    }
  }

  // Unit square with its corner (1,1) cut by a 0.01 m edge, and a 0.05 m square turned 45°
  // poking the chamfer by up to 0.01 m or stopping up to 0.02 m short.
  void chamfer(int count) {
    const std::vector<Point2> a{{0, 0}, {1, 0}, {1, 0.99}, {0.99, 1}, {0, 1}};
    for (int i = 0; i < count; ++i) {
      const double gap = uniform(-0.01, 0.02), along = uniform(-0.006, 0.006);
      const Point2 c{0.995 + (gap + 0.025) * 0.7071067811865476 + along, 0.995 + (gap + 0.025) * 0.7071067811865476 - along};
      const std::vector<Point2> b{{c.x - 0.025, c.y}, {c.x, c.y - 0.025}, {c.x + 0.025, c.y}, {c.x, c.y + 0.025}};
      const double angle = uniform(0, 6.283185307179586);
      add_with_far_copy("chamfer_0.01_" + std::to_string(i), transformed(a, angle, {0, 0}), transformed(b, angle, {0, 0}));
    }
  }

  // A wedge of the given opening along +x with apex at the origin, and one opening along -x
  // with its apex inside or near the first: thin slivers of overlap.
  void wedges(double degrees, int count) {
    const double t = std::tan(degrees * 3.141592653589793 / 360.0);
    const std::vector<Point2> a{{0, 0}, {1, -t}, {1, t}};
    for (int i = 0; i < count; ++i) {
      const double xa = uniform(0.1, 1.3), ya = uniform(-1.5, 1.5) * t * std::min(xa, 1.0);
      const std::vector<Point2> b{{xa, ya}, {xa - 1, ya + t}, {xa - 1, ya - t}};
      const double angle = uniform(0, 6.283185307179586);
      std::ostringstream name;
      name << "wedge_" << degrees << "deg_" << i;
      add_with_far_copy(name.str(), transformed(a, angle, {0, 0}), transformed(b, angle, {0, 0}));
    }
  }

  std::mt19937_64 rng_;
  std::vector<Pair> pairs_;
};

const std::vector<Pair>& test_pairs() {
  static const std::vector<Pair> pairs = Families(seed_for("cgal_reference pairs", 20240701)).all();
  return pairs;
}

// ---------------------------------------------------------------------------------------------
// (a) Entrance block

struct ExactEntrance {
  std::vector<CPoint> vertices;  // E(A, B), strictly convex, CCW
  CPoint a0;
  double scale;                  // largest |coordinate| of B - A (m)
};

ExactEntrance exact_entrance(const ConvexPolygon& a, const ConvexPolygon& b) {
  mpq_class x(0), y(0);
  for (const Point2& p : a.vertices()) x += p.x, y += p.y;
  x /= static_cast<long>(a.size());
  y /= static_cast<long>(a.size());
  const CPolygonWithHoles sum = CGAL::minkowski_sum_2(to_cgal(b), negated(a));
  ExactEntrance e{{}, CPoint(x, y), 0.0};
  for (const CPoint& w : strictly_convex(sum.outer_boundary())) {
    e.scale = std::max({e.scale, std::fabs(w.x().get_d()), std::fabs(w.y().get_d())});
    e.vertices.push_back(CPoint(mpq_class(w.x() + x), mpq_class(w.y() + y)));
  }
  return e;
}

Overlap locate(const ExactEntrance& e) {
  const CPolygon poly(e.vertices.begin(), e.vertices.end());
  switch (poly.bounded_side(e.a0)) {
    case CGAL::ON_BOUNDED_SIDE: return Overlap::overlap;
    case CGAL::ON_BOUNDARY: return Overlap::touch;
    case CGAL::ON_UNBOUNDED_SIDE: break;
  }
  return Overlap::separate;
}

double shortest_edge(const ConvexPolygon& p) {
  double best = INFINITY;
  for (std::size_t k = 0; k < p.size(); ++k) best = std::min(best, std::hypot(p[p.next(k)].x - p[k].x, p[p.next(k)].y - p[k].y));
  return best;
}

double largest_coordinate(const ConvexPolygon& p) {
  double m = 0;
  for (const Point2& v : p.vertices()) m = std::max({m, std::fabs(v.x), std::fabs(v.y)});
  return m;
}

// Is `actual` the exact polygon `expected` up to a cyclic shift, each coordinate equal to the
// nearest double (exact_match) or within `tol` of the exact value? Returns the shift.
template <class Close>
std::optional<std::size_t> cyclic_match(const std::vector<Point2>& actual, const std::vector<CPoint>& expected,
                                        Close close) {
  if (actual.size() != expected.size()) return std::nullopt;
  for (std::size_t s = 0; s < expected.size(); ++s) {
    bool all = true;
    for (std::size_t k = 0; k < actual.size() && all; ++k) all = close(actual[k], expected[(s + k) % expected.size()], k);
    if (all) return s;
  }
  return std::nullopt;
}

bool rounds_to(const Point2& actual, const CPoint& exact) {
  return actual.x == nearest(exact.x()) && actual.y == nearest(exact.y());
}

bool within(const Point2& actual, const CPoint& exact, double tol) {
  return std::fabs(mpq_class(exact.x() - actual.x).get_d()) <= tol &&
         std::fabs(mpq_class(exact.y() - actual.y).get_d()) <= tol;
}

// Is d the double nearest to sqrt(d2)? Its rounding interval [(prev + d)/2, (d + next)/2],
// squared, must contain d2.
bool nearest_sqrt(double d, const mpq_class& d2) {
  const mpq_class lo = (mpq_class(std::nextafter(d, -HUGE_VAL)) + d) / 2;
  const mpq_class hi = (mpq_class(std::nextafter(d, HUGE_VAL)) + d) / 2;
  return (sgn(lo) <= 0 || lo * lo <= d2) && d2 <= hi * hi;
}

template <class Policy>
void check_entrance_block(const Pair& pair, const ExactEntrance& ref, Overlap verdict) {
  const rk::EntranceBlock e = rk::compute_entrance_block<Policy>(pair.a, pair.b);
  const std::string context = std::string(Policy::name) + " " + describe(pair);
  BOOST_TEST_INFO(context);
  BOOST_TEST(to_string(e.status) == to_string(verdict));
  BOOST_TEST_INFO(context);
  BOOST_TEST(to_string(rk::classify_overlap<Policy>(pair.a, pair.b)) == to_string(verdict));

  // Distance from a0 to the boundary of E, exactly: the smallest squared distance to an edge.
  mpq_class d2 = -1;
  for (std::size_t k = 0; k < ref.vertices.size(); ++k) {
    const CSegment edge(ref.vertices[k], ref.vertices[(k + 1) % ref.vertices.size()]);
    const mpq_class s = CGAL::squared_distance(ref.a0, edge);
    if (d2 < 0 || s < d2) d2 = s;
  }
  if constexpr (Policy::kind == rk::PolicyKind::exact) {
    // Each vertex b - a + a0 is exact before its one rounding; the distance is a square root
    // at 256 bits, then rounded once.
    BOOST_TEST_INFO(context);
    BOOST_TEST(cyclic_match(e.vertices, ref.vertices, [](const Point2& p, const CPoint& q, std::size_t) {
                 return rounds_to(p, q);
               }).has_value());
    BOOST_TEST_INFO(context);
    BOOST_TEST(rounds_to(e.reference, ref.a0));
    BOOST_TEST_INFO(context << " distance " << e.distance << " vs sqrt " << d2.get_d());
    BOOST_TEST(nearest_sqrt(e.distance, d2));
  } else {
    // Filtered constructs in double: w = fl(b - a) errs by u|w|, a0 = fl(sum / n) by n u M_A,
    // the vertex fl(w + a0) adds u|vertex|: with M the largest input coordinate (|w| <= 2M,
    // |vertex| <= 3M) the error is below (n + 5) u M; twice that is the tolerance.
    const double M = std::max(largest_coordinate(pair.a), largest_coordinate(pair.b));
    const double tol = 2.0 * static_cast<double>(pair.a.size() + 5) * u * M;
    BOOST_TEST_INFO(context);
    BOOST_TEST(cyclic_match(e.vertices, ref.vertices, [&](const Point2& p, const CPoint& q, std::size_t) {
                 return within(p, q, tol);
               }).has_value());
    BOOST_TEST_INFO(context);
    BOOST_TEST(within(e.reference, ref.a0, tol));
    // The distance is computed from the rounded w (errors <= 2 u W, W the largest |w|): to a
    // segment it is 1-Lipschitz in the vertices; to an edge line (overlap) a vertex error
    // also turns the line, by up to 2 u W / (shortest edge of A or B), which moves it by that
    // angle times W at the reference. The arithmetic adds a few u W. Tolerance:
    // 8 u W (1 + W / shortest edge).
    const double W = ref.scale;
    const double dtol = 8 * u * W * (1 + W / std::min(shortest_edge(pair.a), shortest_edge(pair.b)));
    BOOST_TEST_INFO(context << " distance " << e.distance << " vs " << std::sqrt(d2.get_d()));
    BOOST_TEST(std::fabs(e.distance - std::sqrt(d2.get_d())) <= dtol);
  }
  if (verdict == Overlap::touch) {
    BOOST_TEST_INFO(context);
    BOOST_TEST(e.distance == 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// (b) Intersection polygon

bool on_segment(const CPoint& x, const Point2& p, const Point2& q) { return CSegment(lift(p), lift(q)).has_on(x); }

// Error bound of a Filtered crossing X = t0 + s (t1 - t0), s = N / D, N = l x w, D = l x d
// (l the CP edge, d the TP edge, w = p - t0), all differences rounded. Shewchuk's bound gives
// |dN| <= e N̄ and |dD| <= e D̄ (e = (3 + 16u) u, X̄ the sum of |products|), so
// |ds| <= e (N̄ + |s| D̄) / |D| + u |s|; clamping s to [0, 1] only moves it towards the true
// s. The coordinates add |d| |ds| + 2 u |s d| + u |X|. Twice the sum is the tolerance.
double crossing_tolerance(const Point2& p, const Point2& q, const Point2& t0, const Point2& t1) {
  const double lx = q.x - p.x, ly = q.y - p.y, dx = t1.x - t0.x, dy = t1.y - t0.y;
  const double wx = p.x - t0.x, wy = p.y - t0.y;
  const double N = lx * wy - ly * wx, D = lx * dy - ly * dx;
  const double Nbar = std::fabs(lx * wy) + std::fabs(ly * wx), Dbar = std::fabs(lx * dy) + std::fabs(ly * dx);
  // fmin/fmax map a 0/0 of nearly parallel edges to s = 0 and |ds| = 1: after clamping the
  // point is somewhere on the TP edge, which is then the only bound.
  const double s = std::fmin(std::fmax(N / D, 0.0), 1.0);
  const double e = 4 * u;  // > (3 + 16u) u
  const double ds = std::fmin(e * (Nbar + s * Dbar) / std::fabs(D) + u * s, 1.0);
  const double d = std::max(std::fabs(dx), std::fabs(dy));
  const double x = std::max({std::fabs(t0.x), std::fabs(t0.y), std::fabs(t1.x), std::fabs(t1.y)});
  return 2 * (d * ds + 2 * u * s * d + u * x);
}

template <class Policy>
rk::IntersectionPolygon check_intersection(const std::string& label, const ConvexPolygon& cp, const ConvexPolygon& tp,
                                           const std::vector<CPoint>& ref) {
  const std::string context = std::string(Policy::name) + " " + label;
  const rk::IntersectionPolygon ip = rk::compute_intersection_polygon<Policy>(cp, tp);
  BOOST_TEST_INFO(context << ": IP size " << ip.vertices.size() << " vs exact " << ref.size());
  BOOST_TEST(ip.vertices.size() == ref.size());
  BOOST_TEST(ip.edges.size() == ip.vertices.size());
  if (ip.vertices.size() != ref.size() || ip.edges.size() != ref.size() || ref.empty()) return ip;
  std::vector<Point2> pts;
  rk::construct_points<Policy>(cp, tp, ip, pts);
  BOOST_TEST(pts.size() == ref.size());
  if (pts.size() != ref.size()) return ip;

  const auto close = [&](const Point2& p, const CPoint& x, std::size_t k) {
    const IpVertex& v = ip.vertices[k];
    if (v.kind != IpVertex::Kind::crossing) return p.x == x.x() && p.y == x.y();
    if constexpr (Policy::kind == rk::PolicyKind::exact) {
      return rounds_to(p, x);
    } else {
      return within(p, x, crossing_tolerance(cp[v.cp], cp[cp.next(v.cp)], tp[v.tp], tp[tp.next(v.tp)]));
    }
  };
  const auto shift = cyclic_match(pts, ref, close);
  BOOST_TEST_INFO(context << ": constructed IP does not match the exact intersection");
  BOOST_TEST(shift.has_value());
  if (!shift) return ip;

  const std::size_t n = ref.size();
  for (std::size_t k = 0; k < n; ++k) {
    const CPoint& x = ref[(*shift + k) % n];
    const CPoint& y = ref[(*shift + k + 1) % n];
    const IpVertex& v = ip.vertices[k];
    BOOST_TEST_INFO(context << ": vertex " << k << " label");
    switch (v.kind) {
      case IpVertex::Kind::cp_vertex: BOOST_TEST((x == lift(cp[v.cp]))); break;
      case IpVertex::Kind::tp_vertex: BOOST_TEST((x == lift(tp[v.tp]))); break;
      case IpVertex::Kind::crossing:
        BOOST_TEST((on_segment(x, cp[v.cp], cp[cp.next(v.cp)]) && on_segment(x, tp[v.tp], tp[tp.next(v.tp)])));
        break;
    }
    const IpEdge& edge = ip.edges[k];
    const ConvexPolygon& owner = edge.on == IpEdge::On::cp_edge ? cp : tp;
    const auto j = static_cast<std::size_t>(edge.index);
    BOOST_TEST_INFO(context << ": edge " << k << " lies on " << (edge.on == IpEdge::On::cp_edge ? "CP" : "TP")
                            << " edge " << j);
    BOOST_TEST((on_segment(x, owner[j], owner[owner.next(j)]) && on_segment(y, owner[j], owner[owner.next(j)])));
  }
  return ip;
}

}  // namespace

BOOST_AUTO_TEST_CASE(reference_verdicts_agree_and_constructions_are_what_they_claim) {
  int touching = 0, pushed_in = 0, pushed_out = 0;
  for (const Pair& pair : test_pairs()) {
    const Overlap verdict = reference_verdict(pair.a, pair.b);
    BOOST_TEST_INFO(describe(pair));
    BOOST_TEST(to_string(locate(exact_entrance(pair.a, pair.b))) == to_string(verdict));
    if (pair.name.starts_with("touch_")) {
      BOOST_TEST_INFO(describe(pair));
      BOOST_TEST(to_string(verdict) == "touch");
      ++touching;
    } else if (pair.name.starts_with("vertex_on_edge_pushed_in")) {
      BOOST_TEST_INFO(describe(pair));
      BOOST_TEST(to_string(verdict) == "overlap");
      ++pushed_in;
    } else if (pair.name.starts_with("vertex_on_edge_pushed_out")) {
      BOOST_TEST_INFO(describe(pair));
      BOOST_TEST(to_string(verdict) == "separate");
      ++pushed_out;
    }
  }
  BOOST_TEST_MESSAGE(test_pairs().size() << " pairs; " << touching << " built touching, " << pushed_in
                                         << " pushed in, " << pushed_out << " pushed out");
  BOOST_TEST(touching > 0);
}

BOOST_AUTO_TEST_CASE(entrance_block_matches_minkowski_sum) {
  int counts[3] = {0, 0, 0};
  int float_wrong = 0;
  for (const Pair& pair : test_pairs()) {
    const ExactEntrance ref = exact_entrance(pair.a, pair.b);
    const Overlap verdict = locate(ref);
    ++counts[static_cast<int>(verdict)];
    check_entrance_block<rk::Filtered>(pair, ref, verdict);
    check_entrance_block<rk::Exact>(pair, ref, verdict);
    float_wrong += rk::classify_overlap<rk::Float>(pair.a, pair.b) != verdict;
  }
  BOOST_TEST_MESSAGE("entrance block: " << counts[0] << " separate, " << counts[1] << " touch, " << counts[2]
                                        << " overlap; Float verdict wrong on " << float_wrong);
}

BOOST_AUTO_TEST_CASE(intersection_polygon_matches_boolean_intersection) {
  int nonempty = 0, float_size_wrong = 0, compared = 0;
  for (const Pair& pair : test_pairs()) {
    for (const bool swap : {false, true}) {
      const ConvexPolygon& cp = swap ? pair.b : pair.a;
      const ConvexPolygon& tp = swap ? pair.a : pair.b;
      const std::string label = describe(pair) + (swap ? " (CP = B)" : " (CP = A)");
      const std::vector<CPoint> ref = exact_intersection(cp, tp);
      const rk::IntersectionPolygon filtered = check_intersection<rk::Filtered>(label, cp, tp, ref);
      const rk::IntersectionPolygon exact = check_intersection<rk::Exact>(label, cp, tp, ref);
      // Both follow exact predicates: the symbolic polygons are identical.
      BOOST_TEST_INFO(label);
      BOOST_TEST((filtered.vertices == exact.vertices && filtered.edges == exact.edges));
      // Empty exactly when the verdict is not `overlap`.
      BOOST_TEST_INFO(label);
      BOOST_TEST(ref.empty() == (rk::classify_overlap<rk::Exact>(cp, tp) != Overlap::overlap));
      float_size_wrong += rk::compute_intersection_polygon<rk::Float>(cp, tp).vertices.size() != ref.size();
      nonempty += !ref.empty();
      ++compared;
    }
  }
  BOOST_TEST_MESSAGE("intersection polygon: " << compared << " clippings, " << nonempty
                                              << " with positive area; Float vertex count wrong on "
                                              << float_size_wrong);
}
