#define BOOST_TEST_MODULE kernel_potential
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/hull2.hpp"
#include "rockcontact/testing/seed.hpp"

// The shortest-exit potential (seed 000 eq. 12-14), its demarcation points (§3.2.3) and the
// polygon moments, against analytic references:
//   * exit_distance on a rectangle (the smallest of the four axis distances) and at the
//     incentre of triangles (the inradius 2 S / perimeter);
//   * exact demarcation vs dense sampling of d_exit along the segment, evaluated here in long
//     double: d_exit is concave along a segment, so its second differences are <= 0 and
//     non-zero exactly on the windows that contain a kink;
//   * paper demarcation: on triangles it contains every exact breakpoint (all medial-axis
//     branches of a triangle are vertex bisectors); on a rectangle it misses the central
//     medial-axis segment, and on a chamfered rectangle the virtual node restores the
//     branch that the unbounded bisector rays miss — both asserted with analytic breakpoints;
//   * moments of a rectangle and a right triangle in closed form, and of general and
//     far-from-origin polygons against a fan-of-triangles formula in GMP rationals.

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/2d/detail/potential_impl.hpp"
#include "rockcontact/kernel/2d/moments.hpp"
#include "rockcontact/kernel/2d/potential.hpp"

namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::Demarcation;
using rk::Point2;

namespace {

using rockcontact::testing::seed_for;

constexpr double u = rockcontact::testing::unit_roundoff;

ConvexPolygon rectangle(double x0, double x1, double y0, double y1) {
  return ConvexPolygon::make("rectangle", {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

// d_exit by its definition (eq. 13-14) in long double: the smallest signed distance to an
// edge line, positive inside.
long double reference_exit_distance(const ConvexPolygon& poly, long double x, long double y) {
  long double best = INFINITY;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2 &p = poly[k], &q = poly[poly.next(k)];
    const long double ex = static_cast<long double>(q.x) - p.x, ey = static_cast<long double>(q.y) - p.y;
    const long double d = (ex * (y - p.y) - ey * (x - p.x)) / std::sqrt(ex * ex + ey * ey);
    best = std::min(best, d);
  }
  return best;
}

long double sample(const ConvexPolygon& poly, const Point2& a, const Point2& b, long double t) {
  return reference_exit_distance(poly, a.x + t * (static_cast<long double>(b.x) - a.x),
                                 a.y + t * (static_cast<long double>(b.y) - a.y));
}

// Checks exact-mode breakpoints `t` of segment a b against dense sampling:
//  1. every window [t_{i-1}, t_{i+1}] whose second difference is clearly negative contains a
//     breakpoint (no kink missed);
//  2. every breakpoint lies in a window with a clearly negative second difference (no
//     spurious breakpoint);
//  3. each breakpoint is where the two neighbouring linear pieces meet: lines through two
//     samples on each side (inside the neighbouring pieces) intersect within 1e-10 of it.
// Threshold: long double evaluation errs by ~1e-19 * scale per sample, so a second
// difference below -1e-15 * scale is a kink of slope change at least ~1e-11 per unit t.
void check_exact_breakpoints(const std::string& name, const ConvexPolygon& poly, const Point2& a, const Point2& b) {
  const std::vector<double> t = rk::demarcation_parameters(poly, a, b, Demarcation::exact, 0.0);
  BOOST_TEST_INFO(name);
  BOOST_TEST(std::is_sorted(t.begin(), t.end()));
  for (double x : t) {
    BOOST_TEST_INFO(name << " t = " << x);
    BOOST_TEST((x > 0.0 && x < 1.0));
  }
  const int n = 8192;
  const long double h = 1.0L / n;
  double scale = 0.0;
  for (const Point2& v : poly.vertices()) scale = std::max({scale, std::fabs(v.x), std::fabs(v.y)});
  const long double threshold = 1e-15L * scale;
  std::vector<long double> d(n + 1);
  for (int i = 0; i <= n; ++i) d[i] = sample(poly, a, b, i * h);
  const double slack = 1e-12;  // the library's breakpoints are doubles: tiny overhang allowed
  const auto has_breakpoint_in = [&](long double lo, long double hi) {
    return std::any_of(t.begin(), t.end(), [&](double x) { return x >= lo - slack && x <= hi + slack; });
  };
  std::vector<bool> kink(n + 1, false);
  for (int i = 1; i < n; ++i) {
    const long double second = d[i - 1] - 2 * d[i] + d[i + 1];
    BOOST_TEST_INFO(name << " window " << i << " second difference " << static_cast<double>(second));
    BOOST_TEST(static_cast<double>(second) <= static_cast<double>(threshold));  // concavity
    kink[i] = second < -threshold;
    if (kink[i]) {
      BOOST_TEST_INFO(name << ": kink in window around t = " << static_cast<double>(i * h) << " not reported");
      BOOST_TEST(has_breakpoint_in((i - 1) * h, (i + 1) * h));
    }
  }
  for (std::size_t k = 0; k < t.size(); ++k) {
    const int i = static_cast<int>(std::floor(t[k] * n));
    const bool seen = (i >= 1 && kink[i]) || (i + 1 < n && kink[i + 1]);
    BOOST_TEST_INFO(name << ": breakpoint t = " << t[k] << " has no kink around it");
    BOOST_TEST(seen);
    const long double lo = k == 0 ? 0.0L : t[k - 1], hi = k + 1 == t.size() ? 1.0L : t[k + 1];
    const long double l1 = t[k] - (t[k] - lo) / 3, l2 = t[k] - 2 * (t[k] - lo) / 3;
    const long double r1 = t[k] + (hi - t[k]) / 3, r2 = t[k] + 2 * (hi - t[k]) / 3;
    const long double sl = (sample(poly, a, b, l1) - sample(poly, a, b, l2)) / (l1 - l2);
    const long double sr = (sample(poly, a, b, r2) - sample(poly, a, b, r1)) / (r2 - r1);
    // Left line: d(l1) + sl (x - l1); right line: d(r1) + sr (x - r1).
    const long double meet =
        (sample(poly, a, b, r1) - sr * r1 - sample(poly, a, b, l1) + sl * l1) / (sl - sr);
    BOOST_TEST_INFO(name << ": pieces around t = " << t[k] << " meet at " << static_cast<double>(meet));
    BOOST_TEST(std::fabs(static_cast<double>(meet) - t[k]) <= 1e-10);
  }
}

bool contains(const std::vector<double>& set, double x, double tol) {
  return std::any_of(set.begin(), set.end(), [&](double y) { return std::fabs(x - y) <= tol; });
}

void check_parameters(const std::string& name, const std::vector<double>& actual, const std::vector<double>& expected,
                      double tol) {
  BOOST_TEST_INFO(name);
  BOOST_TEST_REQUIRE(actual.size() == expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    BOOST_TEST_INFO(name << " [" << i << "] " << actual[i] << " vs " << expected[i]);
    BOOST_TEST(std::fabs(actual[i] - expected[i]) <= tol);
  }
}

// A random convex polygon: n points on an ellipse at sorted random angles (retried until the
// rounded vertices are strictly convex).
ConvexPolygon random_convex(std::mt19937_64& rng, int n, double cx, double cy) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (;;) {
    std::vector<double> angle(n);
    for (double& x : angle) x = 6.283185307179586 * unit(rng);
    std::sort(angle.begin(), angle.end());
    const double ra = 0.5 + unit(rng), rb = 0.5 + unit(rng), tilt = unit(rng);
    std::vector<Point2> v;
    for (double x : angle) {
      const double px = ra * std::cos(x), py = rb * std::sin(x);
      v.push_back({cx + px * std::cos(tilt) - py * std::sin(tilt), cy + px * std::sin(tilt) + py * std::cos(tilt)});
    }
    try {
      return ConvexPolygon::make("random", v);
    } catch (const rk::InvalidPolygon&) {
    }
  }
}

// A random point of the polygon: a random convex combination of its vertices.
Point2 random_inside(std::mt19937_64& rng, const ConvexPolygon& poly) {
  std::exponential_distribution<double> weight(1.0);
  double total = 0.0, x = 0.0, y = 0.0;
  for (const Point2& v : poly.vertices()) {
    const double w = weight(rng);
    total += w;
    x += w * v.x;
    y += w * v.y;
  }
  return {x / total, y / total};
}

}  // namespace

// d_exit of a rectangle is min(x - x0, x1 - x, y - y0, y1 - y), inside and outside. The library
// forms p - v, one product and one quotient by an edge length that is itself rounded: at most
// four roundings of quantities bounded by M = max |coordinate| + max edge, so 8 u M bounds it.
BOOST_AUTO_TEST_CASE(exit_distance_of_rectangle) {
  const double x0 = -0.3, x1 = 1.7, y0 = 0.25, y1 = 1.05;
  const ConvexPolygon r = rectangle(x0, x1, y0, y1);
  std::mt19937_64 rng(seed_for("exit_distance_of_rectangle", 20240621));
  std::uniform_real_distribution<double> ux(x0 - 0.5, x1 + 0.5), uy(y0 - 0.5, y1 + 0.5);
  const double tol = 8 * u * (1.7 + 2.0);
  for (int i = 0; i < 2000; ++i) {
    const Point2 p{ux(rng), uy(rng)};
    const double expected = std::min({p.x - x0, x1 - p.x, p.y - y0, y1 - p.y});
    BOOST_TEST_INFO("p = (" << p.x << ", " << p.y << ")");
    BOOST_TEST(std::fabs(rk::exit_distance(r, p) - expected) <= tol);
  }
  // Named cases: vertices and edge points are exactly on the boundary; the centre is at half
  // the short side; a point 0.5 right of the right edge is at -0.5.
  for (const Point2& v : r.vertices()) BOOST_TEST(rk::exit_distance(r, v) == 0.0);
  BOOST_TEST(std::fabs(rk::exit_distance(r, {0.7, 0.65}) - 0.4) <= tol);
  BOOST_TEST(std::fabs(rk::exit_distance(r, {x1 + 0.5, 0.65}) + 0.5) <= tol);
  // phi = kn d / H (eq. 14).
  BOOST_TEST(std::fabs(rk::potential(r, {0.7, 0.65}, 1e7, 0.5) - 1e7 * 0.4 / 0.5) <= 1e7 / 0.5 * tol);
}

// At the incentre I = (a A + b B + c C) / (a + b + c) every edge line is at the inradius
// r = 2 S / (a + b + c), the maximum of d_exit. For the 3-4-5 triangle I = (1, 1), r = 1 and
// every step of the library is exact. For a general triangle I carries a relative error of a
// few u (long double reference, then rounded once): tolerance 16 u times the size.
BOOST_AUTO_TEST_CASE(exit_distance_at_incentre_is_inradius) {
  const ConvexPolygon t345 = ConvexPolygon::make("3-4-5", {{0, 0}, {4, 0}, {0, 3}});
  BOOST_TEST(rk::exit_distance(t345, {1, 1}) == 1.0);

  std::mt19937_64 rng(seed_for("exit_distance_at_incentre_is_inradius", 20240622));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Point2> v{{unit(rng), unit(rng)}, {unit(rng), unit(rng)}, {unit(rng), unit(rng)}};
    ConvexPolygon tri = [&] {
      for (;;) {
        try {
          return ConvexPolygon::make("triangle", v, rk::VertexOrder::normalise);
        } catch (const rk::InvalidPolygon&) {
          v = {{unit(rng), unit(rng)}, {unit(rng), unit(rng)}, {unit(rng), unit(rng)}};
        }
      }
    }();
    using LD = long double;
    const auto len = [](const Point2& p, const Point2& q) { return std::hypot(LD(q.x) - p.x, LD(q.y) - p.y); };
    const Point2 &A = tri[0], &B = tri[1], &C = tri[2];
    const LD a = len(B, C), b = len(C, A), c = len(A, B), per = a + b + c;
    const LD area = ((LD(B.x) - A.x) * (LD(C.y) - A.y) - (LD(B.y) - A.y) * (LD(C.x) - A.x)) / 2;
    const Point2 incentre{static_cast<double>((a * A.x + b * B.x + c * C.x) / per),
                          static_cast<double>((a * A.y + b * B.y + c * C.y) / per)};
    const double r = static_cast<double>(2 * area / per);
    const double tol = 16 * u * 2.0;
    BOOST_TEST_INFO("trial " << trial << " r = " << r);
    BOOST_TEST(std::fabs(rk::exit_distance(tri, incentre) - r) <= tol);
    // The incentre is the maximum: any step of 1e-6 lowers d_exit by at least
    // 1e-6 * min over directions of max_k n_k . v > 0 (well above rounding for these shapes).
    for (int k = 0; k < 8; ++k) {
      const double angle = k * 0.7853981633974483;
      const Point2 moved{incentre.x + 1e-6 * std::cos(angle), incentre.y + 1e-6 * std::sin(angle)};
      BOOST_TEST(rk::exit_distance(tri, moved) < rk::exit_distance(tri, incentre));
    }
  }
}

BOOST_AUTO_TEST_CASE(exact_demarcation_matches_dense_sampling) {
  std::mt19937_64 rng(seed_for("exact_demarcation_matches_dense_sampling", 20240623));
  const ConvexPolygon rect = rectangle(0, 2, 0, 1);
  // Named segments: in the 2 x 1 rectangle a diagonal, one crossing the central medial-axis
  // segment, one along the bottom edge (d_exit = 0: no kink), one crossing two corner
  // bisectors; near a 0.01 m chamfer; along and across a 5 degree wedge; then random chords
  // of random convex polygons.
  check_exact_breakpoints("rectangle diagonal", rect, {0.1, 0.05}, {1.9, 0.95});
  check_exact_breakpoints("rectangle vertical through central axis", rect, {1, 0.75}, {1, 0});
  check_exact_breakpoints("rectangle along bottom edge", rect, {0.1, 0}, {1.9, 0});
  check_exact_breakpoints("rectangle horizontal y = 0.25", rect, {0.1, 0.25}, {1.9, 0.25});
  const ConvexPolygon chamfered =
      ConvexPolygon::make("chamfered", {{0, 0}, {2, 0}, {2, 0.99}, {1.99, 1}, {0, 1}});
  check_exact_breakpoints("chamfered horizontal y = 0.75", chamfered, {1.3, 0.75}, {1.95, 0.75});
  check_exact_breakpoints("chamfered near the 0.01 m edge", chamfered, {1.9, 0.9}, {1.995, 0.999});
  const ConvexPolygon wedge = ConvexPolygon::make("5 degree wedge", {{0, 0}, {1, -0.0436609}, {1, 0.0436609}});
  check_exact_breakpoints("wedge along its axis", wedge, {0.01, 0}, {0.99, 0.0});
  check_exact_breakpoints("wedge across", wedge, {0.5, -0.02}, {0.9, 0.03});
  for (int trial = 0; trial < 40; ++trial) {
    const ConvexPolygon poly = random_convex(rng, 3 + trial % 6, 0.0, 0.0);
    check_exact_breakpoints("random " + std::to_string(trial), poly, random_inside(rng, poly),
                            random_inside(rng, poly));
  }
}

// Lattice polygons (vertices on (Z/8)^2) have medial-axis vertices where three or more
// edge-distance lines meet exactly; their crossing parameters are equal in exact arithmetic
// but round differently, and an envelope that decided on the rounded parameters took a line of
// the wrong slope at such a point and missed the next kink (campaign seed 20261124,
// lattice_touch pair 394832: the named chord below, a side of that pair's IP, has its triple
// point at t = 2/9 and a kink at t = 0.6014 that went missing). Chords with lattice end points
// (step 1/16) of random lattice polygons pass through such points often.
namespace {

// Strict and counter-clockwise; exact on this grid (convex_hull2's orientation test is).
std::vector<Point2> lattice_hull(std::vector<Point2> points) {
  return rockcontact::testing::convex_hull2(std::move(points));
}

}  // namespace

BOOST_AUTO_TEST_CASE(exact_demarcation_on_lattice_polygons_with_concurrent_lines) {
  const ConvexPolygon named = ConvexPolygon::make(
      "lattice_touch 394832 cp", {{0.125, 1}, {0.125, 0.5}, {0.375, 0}, {0.875, 0.125}, {0.75, 0.5}, {0.375, 1}});
  check_exact_breakpoints("lattice chord through a triple point", named, {0.26785714285714285, 1.0}, {0.375, 0.25});
  std::mt19937_64 rng(seed_for("exact_demarcation_on_lattice_polygons_with_concurrent_lines", 20261124));
  std::uniform_int_distribution<int> coordinate(0, 8);
  int polygons = 0;
  while (polygons < 60) {
    std::vector<Point2> points;
    for (int k = 0; k < 8; ++k) points.push_back({coordinate(rng) / 8.0, coordinate(rng) / 8.0});
    const std::vector<Point2> hull = lattice_hull(points);
    if (hull.size() < 3) continue;
    const ConvexPolygon poly = ConvexPolygon::make("lattice", hull);
    ++polygons;
    std::uniform_int_distribution<int> fine(0, 16);
    for (int chord = 0; chord < 4;) {
      const Point2 a{fine(rng) / 16.0, fine(rng) / 16.0}, b{fine(rng) / 16.0, fine(rng) / 16.0};
      if (a == b || rk::exit_distance(poly, a) < 0 || rk::exit_distance(poly, b) < 0) continue;
      check_exact_breakpoints("lattice polygon " + std::to_string(polygons) + " chord " + std::to_string(chord), poly, a, b);
      ++chord;
    }
  }
}

// Coefficients beyond double's range (coordinates past ~1e150 m overflow the cross products)
// have no value for Filtered's exact stage to decide on; handing an infinity to it aborted
// inside GMP (found by fuzz_pair_kernel). The envelope then orders the lines by Float's
// orientation, which still knows that a line at +infinity is never the lowest: with
// d0 = +inf, d1 = t, d2 = 1 - t the only breakpoint is where d1 = d2, t = 1/2 exactly.
BOOST_AUTO_TEST_CASE(envelope_with_an_infinite_coefficient_decides_in_double) {
  rk::detail::LinearPieces<double> lines;
  lines.alpha = {HUGE_VAL, 0.0, 1.0};
  lines.beta = {0.0, 1.0, -1.0};
  std::vector<double> t;
  rk::detail::envelope_breakpoints<rk::Filtered>(lines, t);
  BOOST_TEST(t == std::vector<double>{0.5}, boost::test_tools::per_element());
}

// Triangles: the medial axis is the three vertex bisectors up to the incentre, so the paper's
// bisector rays (unbounded, plus the segment centre) contain every exact breakpoint; the extra
// points only split linear pieces. With an edge shorter than small_edge the virtual node of a
// triangle is its incentre, and the continuing ray lies on the opposite vertex's bisector.
//
// Tolerance: both modes construct in double. The exact breakpoint (envelope of two distance
// functions) is accurate to ~1e-13 here; the paper point is the crossing with a ray whose
// direction r = n_i + n_j is the sum of two rounded unit normals (error ~4u), so its angle errs
// by ~4u / |r|, and |r| = 2 sin(angle / 2) is small at a sharp vertex. That angle, times the
// distance from the vertex to the crossing, over the sine of the angle between the segment and
// the ray, is the displacement along the segment; divided by |b - a| it is δt. The test allows
// 4 δt + 1e-12: sliver triangles crossed at a grazing angle need ~1e-8, a missed kink is O(1).
namespace {

// The vertex whose bisector carries the kink at t: the one shared by the two edges nearest to
// the point (in a triangle any two edges share a vertex), and the allowed error of t.
double paper_tolerance(const ConvexPolygon& tri, const Point2& a, const Point2& b, double t) {
  using LD = long double;
  const LD x = a.x + t * (LD(b.x) - a.x), y = a.y + t * (LD(b.y) - a.y);
  std::array<LD, 3> d{};
  std::array<std::array<LD, 2>, 3> normal{};
  for (std::size_t k = 0; k < 3; ++k) {
    const Point2 &p = tri[k], &q = tri[tri.next(k)];
    const LD ex = LD(q.x) - p.x, ey = LD(q.y) - p.y, len = std::sqrt(ex * ex + ey * ey);
    d[k] = (ex * (y - p.y) - ey * (x - p.x)) / len;
    normal[k] = {-ey / len, ex / len};
  }
  const std::size_t far = static_cast<std::size_t>(std::max_element(d.begin(), d.end()) - d.begin());
  const std::size_t i = tri.next(far), j = tri.next(i);  // the two nearest edges; vertex j joins them
  const LD rx = normal[i][0] + normal[j][0], ry = normal[i][1] + normal[j][1], r = std::hypot(rx, ry);
  const LD sx = LD(b.x) - a.x, sy = LD(b.y) - a.y, s = std::hypot(sx, sy);
  const LD sine = std::fabs(sx * ry - sy * rx) / (s * r);
  const LD lever = std::hypot(x - tri[j].x, y - tri[j].y);
  const LD dt = 4 * u / r * lever / (sine * s);
  return static_cast<double>(4 * dt) + 1e-12;
}

}  // namespace

BOOST_AUTO_TEST_CASE(paper_demarcation_on_triangles_contains_exact) {
  std::mt19937_64 rng(seed_for("paper_demarcation_on_triangles_contains_exact", 20240624));
  double loosest = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const ConvexPolygon tri = random_convex(rng, 3, 0.0, 0.0);
    const Point2 a = random_inside(rng, tri), b = random_inside(rng, tri);
    const std::vector<double> exact = rk::demarcation_parameters(tri, a, b, Demarcation::exact, 0.0);
    double shortest = INFINITY;
    for (std::size_t k = 0; k < 3; ++k) {
      shortest = std::min(shortest, std::hypot(tri[tri.next(k)].x - tri[k].x, tri[tri.next(k)].y - tri[k].y));
    }
    for (const double small_edge : {0.0, 1.01 * shortest}) {
      const std::vector<double> paper = rk::demarcation_parameters(tri, a, b, Demarcation::paper, small_edge);
      BOOST_TEST_INFO("trial " << trial << " small_edge " << small_edge);
      BOOST_TEST(contains(paper, 0.5, 0.0));
      for (double t : exact) {
        const double tol = paper_tolerance(tri, a, b, t);
        loosest = std::max(loosest, tol);
        BOOST_TEST_INFO("trial " << trial << " small_edge " << small_edge << " exact t = " << t << " tol " << tol);
        BOOST_TEST(contains(paper, t, tol));
      }
    }
  }
  BOOST_TEST_MESSAGE("paper vs exact on triangles: loosest tolerance used " << loosest);
}

// The 2 x 1 rectangle [0,2] x [0,1]. Its medial axis: bisectors from the corners to (0.5, 0.5)
// and (1.5, 0.5), joined by the central segment y = 0.5. The paper's rays are the corner
// bisectors continued without end; the central segment is missing.
//  * Segment (1, 0.75) -> (1, 0): d_exit = min(y, 1 - y) kinks at y = 0.5 (central segment),
//    t = 1/3. Paper: only the centre t = 1/2 (the rays meet x = 1 at y = 0 or 1, the ends).
//  * Segment (0.1, 0.25) -> (1.9, 0.25): d_exit = min(x, 0.25, 2 - x) kinks at x = 0.25 and
//    x = 1.75, t = 1/12 and 11/12. Paper: the rays from (0,0), (0,1), (2,1), (2,0) meet
//    y = 0.25 at x = 0.25, 0.75, 1.25, 1.75 (two of them beyond the medial axis), plus the
//    centre x = 1: t = 1/12, 13/36, 1/2, 23/36, 11/12.
// Chamfered rectangle (corner (2,1) cut by a 0.01 m edge from (2, 0.99) to (1.99, 1)): its
// medial axis near the chamfer is the two end-node bisectors up to their meeting point (on the
// line y = x - 1 by symmetry), then y = x - 1 down to (1.5, 0.5). Along (1.3, 0.75) ->
// (1.95, 0.75) d_exit = min(0.25, 2 - x) kinks at x = 1.75 (t = 9/13) only. Without a virtual
// node (small_edge = 0) no paper ray runs along y = x - 1 there: the kink is missed. With
// small_edge = 0.1 > 0.01 sqrt 2 the virtual node's continuing ray is exactly that branch.
BOOST_AUTO_TEST_CASE(paper_demarcation_on_rectangles_documents_missing_branches) {
  const ConvexPolygon rect = rectangle(0, 2, 0, 1);
  const double tol = 1e-14;  // parameters are O(1) quotients of a few rounded terms
  check_parameters("rectangle vertical, exact",
                   rk::demarcation_parameters(rect, {1, 0.75}, {1, 0}, Demarcation::exact, 0.0), {1.0 / 3}, tol);
  check_parameters("rectangle vertical, paper",
                   rk::demarcation_parameters(rect, {1, 0.75}, {1, 0}, Demarcation::paper, 0.1), {0.5}, tol);
  check_parameters("rectangle horizontal, exact",
                   rk::demarcation_parameters(rect, {0.1, 0.25}, {1.9, 0.25}, Demarcation::exact, 0.0),
                   {1.0 / 12, 11.0 / 12}, tol);
  check_parameters("rectangle horizontal, paper",
                   rk::demarcation_parameters(rect, {0.1, 0.25}, {1.9, 0.25}, Demarcation::paper, 0.1),
                   {1.0 / 12, 13.0 / 36, 0.5, 23.0 / 36, 11.0 / 12}, tol);

  const ConvexPolygon chamfered =
      ConvexPolygon::make("chamfered", {{0, 0}, {2, 0}, {2, 0.99}, {1.99, 1}, {0, 1}});
  const Point2 a{1.3, 0.75}, b{1.95, 0.75};
  check_parameters("chamfered, exact", rk::demarcation_parameters(chamfered, a, b, Demarcation::exact, 0.0),
                   {9.0 / 13}, tol);
  const std::vector<double> no_virtual = rk::demarcation_parameters(chamfered, a, b, Demarcation::paper, 0.0);
  const std::vector<double> with_virtual = rk::demarcation_parameters(chamfered, a, b, Demarcation::paper, 0.1);
  BOOST_TEST(!contains(no_virtual, 9.0 / 13, 1e-6));
  BOOST_TEST(contains(with_virtual, 9.0 / 13, 1e-12));
  BOOST_TEST(contains(with_virtual, 0.5, 0.0));
}

// Closed forms. Rectangle [x0,x1] x [y0,y1]: S = w h, Sx = h (x1² - x0²)/2,
// Sxx = h (x1³ - x0³)/3, Sxy = (x1² - x0²)(y1² - y0²)/4. Right triangle (0,0), (a,0), (0,b):
// S = ab/2, Sx = a²b/6, Sy = ab²/6, Sxx = a³b/12, Syy = ab³/12, Sxy = a²b²/24. Moving by
// (X, Y): Sx' = Sx + X S, Sxx' = Sxx + 2X Sx + X² S, Sxy' = Sxy + X Sy + Y Sx + XY S.
// All evaluated in GMP rationals. Tolerance: with L the largest distance from the first vertex
// (the library's local origin) and M the largest |coordinate| plus L, every Green term of the
// moment of x^i y^j and every parallel-axis term is bounded by 2 L² M^(i+j); n terms of a few
// roundings each, summed, err by at most ~4 n² u times that scale: 1e-13 (~450 u) covers n <= 9.
// (L², not S, is the scale: a thin polygon's area is a cancelling sum of terms of size L².)
namespace {

struct ExactMoments {
  mpq_class S, Sx, Sy, Sxx, Syy, Sxy;
};

ExactMoments shifted(const ExactMoments& m, const mpq_class& X, const mpq_class& Y) {
  return {m.S,
          m.Sx + X * m.S,
          m.Sy + Y * m.S,
          m.Sxx + 2 * X * m.Sx + X * X * m.S,
          m.Syy + 2 * Y * m.Sy + Y * Y * m.S,
          m.Sxy + X * m.Sy + Y * m.Sx + X * Y * m.S};
}

// Fan of triangles (v0, vi, vi+1), each by its vertex formulas:
//   ∫x = A (x1+x2+x3)/3,  ∫x² = A (x1²+x2²+x3²+x1x2+x2x3+x3x1)/6,
//   ∫xy = A (2x1y1+2x2y2+2x3y3+x1y2+x2y1+x1y3+x3y1+x2y3+x3y2)/12, A signed area.
ExactMoments fan_moments(const std::vector<Point2>& v) {
  ExactMoments m{0, 0, 0, 0, 0, 0};
  const mpq_class x1(v[0].x), y1(v[0].y);
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const mpq_class x2(v[i].x), y2(v[i].y), x3(v[i + 1].x), y3(v[i + 1].y);
    const mpq_class A = ((x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1)) / 2;
    m.S += A;
    m.Sx += A * (x1 + x2 + x3) / 3;
    m.Sy += A * (y1 + y2 + y3) / 3;
    m.Sxx += A * (x1 * x1 + x2 * x2 + x3 * x3 + x1 * x2 + x2 * x3 + x3 * x1) / 6;
    m.Syy += A * (y1 * y1 + y2 * y2 + y3 * y3 + y1 * y2 + y2 * y3 + y3 * y1) / 6;
    m.Sxy += A * (2 * x1 * y1 + 2 * x2 * y2 + 2 * x3 * y3 + x1 * y2 + x2 * y1 + x1 * y3 + x3 * y1 + x2 * y3 + x3 * y2) / 12;
  }
  return m;
}

void check_moments(const std::string& name, const std::vector<Point2>& v, const ExactMoments& e) {
  const rk::PolygonMoments m = rk::compute_moments(v);
  double L = 0, M = 0;
  for (const Point2& p : v) {
    L = std::max(L, std::hypot(p.x - v[0].x, p.y - v[0].y));
    M = std::max({M, std::fabs(p.x), std::fabs(p.y)});
  }
  M += L;
  const auto check = [&](const char* what, double actual, const mpq_class& expected, int degree) {
    BOOST_TEST_INFO(name << " " << what << ": " << actual << " vs " << expected.get_d());
    BOOST_TEST(mpq_class(abs(mpq_class(expected - actual))).get_d() <= 1e-13 * 2 * L * L * std::pow(M, degree));
  };
  check("S", m.S, e.S, 0);
  check("Sx", m.Sx, e.Sx, 1);
  check("Sy", m.Sy, e.Sy, 1);
  check("Sxx", m.Sxx, e.Sxx, 2);
  check("Syy", m.Syy, e.Syy, 2);
  check("Sxy", m.Sxy, e.Sxy, 2);
  // The centroid Sx / S: relative errors of S and Sx of ~1e-13 L² / S each.
  const Point2 c = m.centroid();
  const double centroid_tol = 1e-13 * 4 * L * L / std::fabs(e.S.get_d()) * M;
  BOOST_TEST_INFO(name << " centroid");
  BOOST_TEST(std::fabs(c.x - mpq_class(e.Sx / e.S).get_d()) <= centroid_tol);
  BOOST_TEST_INFO(name << " centroid");
  BOOST_TEST(std::fabs(c.y - mpq_class(e.Sy / e.S).get_d()) <= centroid_tol);
}

}  // namespace

BOOST_AUTO_TEST_CASE(moments_match_closed_forms) {
  // Rectangle [x0,x1] x [y0,y1] in closed form.
  const auto rect_moments = [](double x0d, double x1d, double y0d, double y1d) {
    const mpq_class x0(x0d), x1(x1d), y0(y0d), y1(y1d), w = x1 - x0, h = y1 - y0;
    return ExactMoments{w * h,
                        h * (x1 * x1 - x0 * x0) / 2,
                        w * (y1 * y1 - y0 * y0) / 2,
                        h * (x1 * x1 * x1 - x0 * x0 * x0) / 3,
                        w * (y1 * y1 * y1 - y0 * y0 * y0) / 3,
                        (x1 * x1 - x0 * x0) * (y1 * y1 - y0 * y0) / 4};
  };
  check_moments("rectangle", {{-0.3, 0.25}, {1.7, 0.25}, {1.7, 1.05}, {-0.3, 1.05}}, rect_moments(-0.3, 1.7, 0.25, 1.05));
  check_moments("rectangle at 1e6", {{1e6 - 0.3, 1e6 + 0.25}, {1e6 + 1.7, 1e6 + 0.25}, {1e6 + 1.7, 1e6 + 1.05}, {1e6 - 0.3, 1e6 + 1.05}},
                rect_moments(1e6 - 0.3, 1e6 + 1.7, 1e6 + 0.25, 1e6 + 1.05));

  // Right triangle (0,0), (a,0), (0,b) and its copy moved by (X, Y) = (1e6, -2e6) (exact:
  // integers plus these a, b stay within 53 bits).
  const double ad = 1.25, bd = 0.75;
  const mpq_class a(ad), b(bd);
  const ExactMoments tri{a * b / 2, a * a * b / 6, a * b * b / 6, a * a * a * b / 12, a * b * b * b / 12, a * a * b * b / 24};
  check_moments("right triangle", {{0, 0}, {ad, 0}, {0, bd}}, tri);
  check_moments("right triangle at (1e6, -2e6)", {{1e6, -2e6}, {1e6 + ad, -2e6}, {1e6, -2e6 + bd}},
                shifted(tri, mpq_class(1e6), mpq_class(-2e6)));
  // The fan formula agrees with the closed form (a check of the reference itself).
  const ExactMoments fan = fan_moments({{0, 0}, {ad, 0}, {0, bd}});
  BOOST_TEST((fan.S == tri.S && fan.Sx == tri.Sx && fan.Sy == tri.Sy && fan.Sxx == tri.Sxx && fan.Syy == tri.Syy &&
              fan.Sxy == tri.Sxy));
}

BOOST_AUTO_TEST_CASE(moments_of_general_polygons) {
  std::mt19937_64 rng(seed_for("moments_of_general_polygons", 20240625));
  for (int trial = 0; trial < 100; ++trial) {
    const bool far = trial % 2 == 1;
    const ConvexPolygon poly = random_convex(rng, 3 + trial % 7, far ? 1e6 : 0.3, far ? -1e6 : 0.1);
    const std::vector<Point2> v(poly.vertices().begin(), poly.vertices().end());
    check_moments((far ? "far polygon " : "polygon ") + std::to_string(trial), v, fan_moments(v));
  }
}
