#define BOOST_TEST_MODULE kernel_touch_time
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/seed.hpp"

// first_touch and compare_touch (touch_time.hpp, seed 003 §3) against independently computed
// touch times:
//   * analytic oracles: seed 003's CDEM example (a 1 m gap closed at 3 m/s, first touch at
//     t = 1/3 s) and rotating edges designed so that f(s) = -(s - s₀)(s - s₁) with chosen
//     dyadic roots;
//   * by construction: a spinning block whose two vertices touch one edge at the same exact
//     time (a co-rotating target: the relative motion is a translation), then apart by a
//     known sign, 1.5e-12 s and 2e-18 of the step (below the resolution of a rounded s);
//   * a reference in exact rationals (gmpxx), written here without the library's surd
//     algebra: f, G = (p - a)·(b - a) and E = |b - a|² are evaluated from the interpolated
//     positions at s = 0, 1/2, 1 and fitted, their roots bracketed by bisection on the pieces
//     where f is monotone, to 2^-120;
//   * Filtered against Exact (and Checked) on random, far-from-origin and degenerate motions
//     (a node through an edge's end, A = 0, D = 0 grazes), seeded and printed.

#include <gmpxx.h>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/touch_time.hpp"

namespace rockcontact::kernel {
std::ostream& operator<<(std::ostream& out, Sign s) { return out << static_cast<int>(s); }
}  // namespace rockcontact::kernel

namespace rk = rockcontact::kernel;
using rk::MovingPoint2;
using rk::NodeEdgeMotion;
using rk::Point2;
using rk::Sign;
using rk::TouchTime;

namespace {

using rockcontact::testing::seed_for;
constexpr double u = rockcontact::testing::unit_roundoff;  // 2^-53

NodeEdgeMotion motion(Point2 p0, Point2 p1, Point2 a0, Point2 a1, Point2 b0, Point2 b1) {
  return {{p0, p1}, {a0, a1}, {b0, b1}};
}

// Runs f(P{}) for each listed policy, in a test context naming it.
template <class... Policies, class F>
void for_policies(const F& f) {
  (
      [&] {
        BOOST_TEST_CONTEXT("policy " << Policies::name) { f(Policies{}); }
      }(),
      ...);
}

// ---------------------------------------------------------------------------------------------
// The reference in exact rationals.

using Q = mpq_class;

struct QVec {
  Q x, y;
};

QVec position(const MovingPoint2& q, const Q& s) {
  return {Q(q.start.x) + s * (Q(q.end.x) - Q(q.start.x)), Q(q.start.y) + s * (Q(q.end.y) - Q(q.start.y))};
}

struct QQuadratic {
  Q c2, c1, c0;
  Q at(const Q& s) const { return (c2 * s + c1) * s + c0; }
};

// The quadratic through q(0) = v0, q(1/2) = vh, q(1) = v1.
QQuadratic fit(const Q& v0, const Q& vh, const Q& v1) {
  return {2 * v1 - 4 * vh + 2 * v0, 4 * vh - v1 - 3 * v0, v0};
}

struct Reference {
  QQuadratic f, g, e;  // (b - a) x (p - a), (p - a)·(b - a), |b - a|²
};

Reference reference(const NodeEdgeMotion& m) {
  Q f[3], g[3], e[3];
  const Q instants[3] = {Q(0), Q(1) / 2, Q(1)};
  for (int i = 0; i < 3; ++i) {
    const QVec p = position(m.node, instants[i]), a = position(m.a, instants[i]),
               b = position(m.b, instants[i]);
    const QVec ab{b.x - a.x, b.y - a.y}, ap{p.x - a.x, p.y - a.y};
    f[i] = ab.x * ap.y - ab.y * ap.x;
    g[i] = ap.x * ab.x + ap.y * ab.y;
    e[i] = ab.x * ab.x + ab.y * ab.y;
  }
  return {fit(f[0], f[1], f[2]), fit(g[0], g[1], g[2]), fit(e[0], e[1], e[2])};
}

// The first touch in (0, 1] bracketed in [lo, hi] (lo == hi: the exact root), no touch, or
// undecided: the span condition changes sign inside the bracket (never seen on the inputs here
// except exact end-point touches, whose bracket is exact).
struct ReferenceTouch {
  enum Status { none, touch, undecided } status = none;
  Q lo, hi;
};

constexpr int reference_bisections = 120;

ReferenceTouch reference_first_touch(const NodeEdgeMotion& m) {
  const Reference r = reference(m);
  if (sgn(r.f.c0) >= 0) return {};
  // f is monotone on each piece of [0, 1] cut at its critical point -B / (2A).
  std::vector<Q> cuts{Q(0)};
  if (sgn(r.f.c2) != 0) {
    const Q critical = -r.f.c1 / (2 * r.f.c2);
    if (critical > 0 && critical < 1) cuts.push_back(critical);
  }
  cuts.push_back(Q(1));
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    Q lo = cuts[i], hi = cuts[i + 1];
    const int at_lo = sgn(r.f.at(lo)), at_hi = sgn(r.f.at(hi));
    if (at_hi == 0) {
      lo = hi;
    } else if (at_lo * at_hi < 0) {
      for (int k = 0; k < reference_bisections; ++k) {
        const Q mid = (lo + hi) / 2;
        const int at_mid = sgn(r.f.at(mid));
        if (at_mid == 0) {
          lo = hi = mid;
          break;
        }
        (at_mid == at_lo ? lo : hi) = mid;
      }
    } else {
      continue;
    }
    // The span condition G >= 0, E - G >= 0, at both ends of the bracket.
    const auto side = [&](const Q& s) {
      const int g = sgn(r.g.at(s)), h = sgn(r.e.at(s) - r.g.at(s));
      return (g < 0 || h < 0) ? -1 : ((g == 0 || h == 0) ? 0 : 1);
    };
    const int side_lo = side(lo), side_hi = side(hi);
    if (lo != hi && (side_lo != side_hi || side_lo == 0)) return {ReferenceTouch::undecided, lo, hi};
    if (side_lo >= 0) return {ReferenceTouch::touch, lo, hi};
  }
  return {};
}

// The exact order of two reference touches; nullopt when the brackets overlap but differ.
std::optional<Sign> reference_order(const ReferenceTouch& x, const ReferenceTouch& y) {
  if (x.hi < y.lo) return Sign::negative;
  if (x.lo > y.hi) return Sign::positive;
  if (x.lo == x.hi && y.lo == y.hi && x.lo == y.lo) return Sign::zero;
  return std::nullopt;
}

// An upper bound on |value - s| for the bracketed root s: the distance to the bracket's far end.
Q distance(double value, const ReferenceTouch& t) {
  const Q to_lo = abs(Q(value) - t.lo), to_hi = abs(Q(value) - t.hi);
  return to_lo > to_hi ? to_lo : to_hi;
}

// |value - λ| with λ = G / E at the bracket's midpoint (within ~2^-118 of λ at the root, far
// below every tolerance used).
Q lambda_distance(double value, const NodeEdgeMotion& m, const ReferenceTouch& t) {
  const Reference r = reference(m);
  const Q s = (t.lo + t.hi) / 2;
  const Q e = r.e.at(s);
  const Q lambda = sgn(e) == 0 ? Q(0) : Q(r.g.at(s) / e);
  return abs(Q(value) - lambda);
}

// Half the spacing of the doubles above x: the error bound of a correct rounding (the spacing
// below is the same or half of it).
Q half_ulp(double x) { return (Q(std::nextafter(x, 2.0)) - Q(x)) / 2; }
double ulp_above(double x) { return std::nextafter(x, 2.0) - x; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// 1. The analytic touch of seed 003's CDEM example.

// A block moving at 3 m/s towards a fixed edge 1 m away touches it at t = 1/3 s. Over the step
// [0.3330, 0.3335] s its vertex moves from x = 3 t - 1 = -0.001 m to 0.0005 m, and the edge
// (the target's left side, a = (0, 1) -> b = (0, -1), its interior on the left of a -> b, x > 0)
// is reached at s = (1/3 - 0.3330) / 0.0005 = 2/3, at the edge's midpoint, λ = 1/2.
// Tolerance 1e-12 relative: the inputs -0.001 and 0.0005 are the doubles nearest to the
// decimals (relative error <= u each), which moves s = 0.001 / 0.0015 by <= 3u relative; Filtered
// adds at most touch_time_tolerance = 2^-44 ≈ 5.7e-14, Exact u, Float a few u: all far inside.
BOOST_AUTO_TEST_CASE(seed003_gap_closed_at_3_m_per_s) {
  const double t0 = 0.3330, t1 = 0.3335;
  const NodeEdgeMotion m =
      motion({-0.001, 0.0}, {0.0005, 0.0}, {0.0, 1.0}, {0.0, 1.0}, {0.0, -1.0}, {0.0, -1.0});
  const double expected = (1.0 / 3.0 - t0) / (t1 - t0);  // in double, 2/3 to ~1e-13
  for_policies<rk::Float, rk::Filtered, rk::Exact, rk::Checked>([&](auto policy) {
    using P = decltype(policy);
    const auto t = rk::first_touch<P>(m);
    BOOST_TEST_REQUIRE(t.has_value());
    BOOST_TEST(std::fabs(t->s - 2.0 / 3.0) <= 1e-12 * (2.0 / 3.0));
    BOOST_TEST(std::fabs(t->s - expected) <= 1e-12 * expected);
    BOOST_TEST(t->lambda == 0.5);  // y = 0 on the edge from y = 1 to y = -1: exact in every policy
    BOOST_TEST(t->root == rk::touch_root_linear);  // a fixed edge: f is linear
    // The same scene 2^20 m up: every coordinate shifts exactly, so does nothing else.
    const auto up = [](Point2 p) { return Point2{p.x, p.y + 0x1p20}; };
    const NodeEdgeMotion far =
        motion(up(m.node.start), up(m.node.end), up(m.a.start), up(m.a.end), up(m.b.start), up(m.b.end));
    const auto t_far = rk::first_touch<P>(far);
    BOOST_TEST_REQUIRE(t_far.has_value());
    BOOST_TEST(t_far->s == t->s);
    BOOST_TEST(t_far->lambda == t->lambda);
  });
  // Exact rounds correctly: s is the double nearest to the root of the input doubles.
  const ReferenceTouch ref = reference_first_touch(m);
  BOOST_TEST_REQUIRE(ref.status == ReferenceTouch::touch);
  BOOST_TEST(distance(rk::first_touch<rk::Exact>(m)->s, ref) <=
             half_ulp(rk::first_touch<rk::Exact>(m)->s) + Q(0x1p-110));
}

// ---------------------------------------------------------------------------------------------
// 2. Rotating edges: a true quadratic.

namespace {

// The family of the rotating-edge tests: a = (0, 0) fixed, b turning from (1, 0) to (1, 1), the
// node from (x, y) to (x + 1, y + v). Then f(s) = y + (v - x) s - s² and, at a root, the node
// is p = (x + s) b, so λ = x + s. With v - x = k: D = k² + 4y.
NodeEdgeMotion rotating_edge(double x, double y, double k) {
  return motion({x, y}, {x + 1.0, y + x + k}, {0.0, 0.0}, {0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0});
}

// The expected touch of a designed case, checked under each policy given.
template <class... Policies>
void expect_touch(const NodeEdgeMotion& m, double s, double lambda, int root, double tolerance) {
  for_policies<Policies...>([&](auto policy) {
    using P = decltype(policy);
    const auto t = rk::first_touch<P>(m);
    BOOST_TEST_REQUIRE(t.has_value());
    BOOST_TEST(std::fabs(t->s - s) <= tolerance * s);
    BOOST_TEST(std::fabs(t->lambda - lambda) <= tolerance);
    BOOST_TEST(t->root == root);
  });
}

template <class... Policies>
void expect_no_touch(const NodeEdgeMotion& m) {
  for_policies<Policies...>([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST(!rk::first_touch<P>(m).has_value());
  });
}

}  // namespace

// f(s) = -(s - 1/4)(s - 3/4): y = -3/16, k = 1. Every value here is dyadic and every operation
// of every policy exact (D = 1/4, √D = 1/2), so the expected values hold to the bit.
BOOST_AUTO_TEST_CASE(rotating_edge_first_of_two_roots) {
  // x = 0: λ = 1/4 at s = 1/4, inside the span: the first root is the touch.
  expect_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.0, -0.1875, 1.0), 0.25, 0.25,
                                                                rk::touch_root_smaller, 0.0);
}

BOOST_AUTO_TEST_CASE(rotating_edge_second_root_when_first_misses_span) {
  // x = -1/2: at s = 1/4 the node crosses the line at λ = -1/4, before the end a; the edge
  // meets it at s = 3/4, λ = 1/4.
  expect_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(-0.5, -0.1875, 1.0), 0.75, 0.25,
                                                                rk::touch_root_larger, 0.0);
  // f(s) = -(s - 1/2)(s - 1) (y = -1/2, k = 3/2), x = -3/4: λ = -1/4 at s = 1/2, λ = 1/4 at
  // s = 1, the end of the step, which is included.
  expect_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(-0.75, -0.5, 1.5), 1.0, 0.25,
                                                                rk::touch_root_larger, 0.0);
}

BOOST_AUTO_TEST_CASE(node_passing_beside_the_edge_never_touches) {
  // x = 1: λ = 5/4 and 7/4, both beyond the end b.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(1.0, -0.1875, 1.0));
  // D < 0 (y = -0.3, k = 1): the node never reaches the line.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.0, -0.3, 1.0));
  // Both roots after the step: f(s) = -(s - 5/4)(s - 3/2), y = -15/8, k = 11/4.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(-1.0, -1.875, 2.75));
  // A fixed edge and a node moving away from it (B < 0), and one moving along it (B = 0).
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(
      motion({-1.0, 0.0}, {-2.0, 0.0}, {0.0, 1.0}, {0.0, 1.0}, {0.0, -1.0}, {0.0, -1.0}));
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(
      motion({-1.0, 0.5}, {-1.0, -0.5}, {0.0, 1.0}, {0.0, 1.0}, {0.0, -1.0}, {0.0, -1.0}));
}

BOOST_AUTO_TEST_CASE(node_starting_on_or_inside_the_line_is_not_a_touch) {
  // y = 0: f(0) = 0, on the line (within the span, λ = 0.5) at the start: an existing contact.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(
      motion({0.5, 0.0}, {0.5, 0.5}, {0.0, 0.0}, {0.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}));
  // y = 1/8 > 0: inside; even though f changes sign later it is not a touch from outside.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.0, 0.125, 1.0));
}

// D = 0: f(s) = -(s - 1/2)² (y = -1/4, k = 1). The node reaches the line at s = 1/2 and turns
// back: a graze, counted as a touch (touch_time.hpp) when within the span. (Every operation is
// exact here, in double as in intervals; the degenerate family of test 4 places grazes where
// the filter has to fall back.)
BOOST_AUTO_TEST_CASE(double_root_graze_counts_as_a_touch) {
  expect_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.0, -0.25, 1.0), 0.5, 0.5,
                                                                rk::touch_root_smaller, 0.0);
  // x = 3/4: the graze at λ = 5/4 is beside the edge.
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.75, -0.25, 1.0));
  // 2^-52 further out: D = 1 + 4y = -2^-50, no root; 2^-52 closer: D = 2^-50, two roots
  // 1/2 ∓ 2^-26, λ = s. (y and the node's end y + 1 = 3/4 ± 2^-52 are doubles, and every
  // operation is exact in double too.)
  expect_no_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(rotating_edge(0.0, -0.25 - 0x1p-52, 1.0));
  expect_touch<rk::Float, rk::Filtered, rk::Exact, rk::Checked>(
      rotating_edge(0.0, -0.25 + 0x1p-52, 1.0), 0.5 - 0x1p-26, 0.5 - 0x1p-26, rk::touch_root_smaller, 0.0);
}

// An irrational root: y = -0.2 (not dyadic), k = 1, roots (1 ∓ √(1 + 4y)) / 2 of the double y;
// x = 0.1. Reference: the rational bracket (2^-120). Exact is the correctly rounded root, hence
// within half an ulp; Filtered within its certified 2^-44 relative; Float within 1e-14 (a few
// roundings of well-conditioned terms, D = 0.2 far from zero: a sanity bound, not a guarantee).
BOOST_AUTO_TEST_CASE(irrational_root_against_the_reference) {
  const NodeEdgeMotion m = rotating_edge(0.1, -0.2, 1.0);
  const ReferenceTouch ref = reference_first_touch(m);
  BOOST_TEST_REQUIRE(ref.status == ReferenceTouch::touch);
  const auto exact = rk::first_touch<rk::Exact>(m);
  BOOST_TEST_REQUIRE(exact.has_value());
  BOOST_TEST(distance(exact->s, ref) <= half_ulp(exact->s) + Q(0x1p-110));
  BOOST_TEST(lambda_distance(exact->lambda, m, ref) <= half_ulp(exact->lambda) + Q(0x1p-100));
  // Filtered: |s' - s| <= 2^-44 s; written with s' for s, which the factor (1 + 2^-40) covers.
  const auto filtered = rk::first_touch<rk::Filtered>(m);
  BOOST_TEST_REQUIRE(filtered.has_value());
  BOOST_TEST(distance(filtered->s, ref) <= Q(rk::touch_time_tolerance * filtered->s * (1 + 0x1p-40)));
  BOOST_TEST(lambda_distance(filtered->lambda, m, ref) <= Q(rk::touch_time_tolerance) + Q(0x1p-100));
  const auto plain = rk::first_touch<rk::Float>(m);
  BOOST_TEST_REQUIRE(plain.has_value());
  BOOST_TEST(distance(plain->s, ref) <= Q(1e-14));
  BOOST_TEST(plain->root == exact->root);
}

// ---------------------------------------------------------------------------------------------
// 3. The order case: a spinning block whose two vertices reach a target edge 1e-12 s apart.

namespace {

// The step: Δt = 1e-4 s. A unit square, its top side y = -gap below the target edge y = 0 from
// a = (-2, 0) to b = (2, 0) (the target above: left of a -> b), moves up by `shift` = 2^-10 m
// (9.8 m/s) and spins by the dyadic map L = [[c, -s], [s, c]], s = 2^-14 (0.61 rad/s), c = 1 -
// 2^-29 (c² + s² = 1 + 2^-58: rigid to 1e-17), about its centre, each vertex moving linearly
// from start to end, as in the engine. The target edge turns about the same centre by its own
// map L_e. Every end position is computed in rationals and is exactly a double (the dyadic
// values have few bits; checked), except the target's in the 1e-12 s case (rounded: the
// reference reads the rounded doubles, and the order there is 10^7 times what rounding moves).
//
// When L_e = L the relative motion is a translation: with M(s) = I + s (L - I), a vertex's
// offset from a is M(s) r0 + s T and the edge is M(s) e0, so f(s) = det M(s) (e0 x r0) +
// s (M(s) e0) x T, a quadratic (det M(s) is one), the same for both top vertices since their
// offsets r0 differ by (1, 0) ∥ e0: their touch times are exactly equal.
constexpr double gap = 0x1p-11 + 0x1p-20;  // m; s ≈ 1/2, irrational
constexpr double shift = 0x1p-10;          // m per step
constexpr double spin_sin = 0x1p-14, spin_cos = 1.0 - 0x1p-29;
const Point2 centre{0.0, -0.5 - gap};

Point2 moved(Point2 start, double c, double s, Point2 translation, bool exact = true) {
  const Q x = Q(start.x) - Q(centre.x), y = Q(start.y) - Q(centre.y);
  const Q ex = Q(centre.x) + Q(c) * x - Q(s) * y + Q(translation.x);
  const Q ey = Q(centre.y) + Q(s) * x + Q(c) * y + Q(translation.y);
  const Point2 end{ex.get_d(), ey.get_d()};
  if (exact) BOOST_TEST_REQUIRE((Q(end.x) == ex && Q(end.y) == ey));  // the construction is exact
  return end;
}

// A top vertex of the spinning square (starting at (±0.5, -gap)) against the target edge
// turning by (edge_cos, edge_sin).
NodeEdgeMotion spinning_vertex(Point2 vertex_start, double edge_cos, double edge_sin) {
  const Point2 a0{-2.0, 0.0}, b0{2.0, 0.0};
  const Point2 vertex_end = moved(vertex_start, spin_cos, spin_sin, {0.0, shift});
  const bool co_rotating = edge_cos == spin_cos && edge_sin == spin_sin;
  return motion(vertex_start, vertex_end, a0, moved(a0, edge_cos, edge_sin, {}, co_rotating), b0,
                moved(b0, edge_cos, edge_sin, {}, co_rotating));
}

// The engine's loop over the candidates: the index of the earliest touch by compare_touch<P>
// (the first of equal ones), -1 if none.
template <class P>
int earliest(const std::vector<NodeEdgeMotion>& motions) {
  int best = -1;
  std::optional<TouchTime> best_touch;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    const auto t = rk::first_touch<P>(motions[i]);
    if (!t) continue;
    if (best < 0 || rk::compare_touch<P>(motions[i], *t, motions[static_cast<std::size_t>(best)],
                                         *best_touch) == Sign::negative) {
      best = static_cast<int>(i);
      best_touch = t;
    }
  }
  return best;
}

// compare_touch<P> on x, y in both orders against the expected sign.
template <class P>
void expect_order(const NodeEdgeMotion& x, const NodeEdgeMotion& y, Sign expected) {
  const auto tx = rk::first_touch<P>(x), ty = rk::first_touch<P>(y);
  BOOST_TEST_REQUIRE((tx.has_value() && ty.has_value()));
  BOOST_TEST(rk::compare_touch<P>(x, *tx, y, *ty) == expected);
  BOOST_TEST(rk::compare_touch<P>(y, *ty, x, *tx) == -expected);
}

}  // namespace

// The edge turns 2^-35 rad per step faster than the block: relative to the block, at s it has
// turned by 2^-35 s more, lowering the edge at the left vertex and raising it at the right one
// by 2^-35 s · 0.5 m each. Against a closing speed of 2^-10 m per step the left vertex touches
// first, by Δs ≈ 2^-35 · (1/2) / 2^-10 = 2^-26 ≈ 1.5e-8, i.e. 1.5e-12 s of the 1e-4 s step.
// Expected sign: by that construction and by the rational reference. Float orders it too (Δs
// is 10^8 ulps of s).
BOOST_AUTO_TEST_CASE(spinning_block_vertices_1e12_s_apart) {
  const double edge_sin = spin_sin + 0x1p-35, edge_cos = 1.0 - 0x1p-29;
  const NodeEdgeMotion left = spinning_vertex({-0.5, -gap}, edge_cos, edge_sin);
  const NodeEdgeMotion right = spinning_vertex({0.5, -gap}, edge_cos, edge_sin);
  const ReferenceTouch ref_left = reference_first_touch(left), ref_right = reference_first_touch(right);
  BOOST_TEST_REQUIRE((ref_left.status == ReferenceTouch::touch && ref_right.status == ReferenceTouch::touch));
  BOOST_TEST_REQUIRE((reference_order(ref_left, ref_right) == std::optional<Sign>(Sign::negative)));
  const double ds = Q(ref_right.lo - ref_left.lo).get_d();
  BOOST_TEST_MESSAGE("vertices 1e-12 s apart: Δs = " << ds << ", Δt = " << ds * 1e-4 << " s");
  BOOST_TEST((ds > 0.5e-8 && ds < 3e-8));
  for_policies<rk::Float, rk::Filtered, rk::Exact, rk::Checked>([&](auto policy) {
    using P = decltype(policy);
    expect_order<P>(left, right, Sign::negative);
    BOOST_TEST(earliest<P>({right, left}) == 1);  // the left vertex, whichever comes first in the list
    BOOST_TEST(earliest<P>({left, right}) == 0);
  });
}

// Below double resolution: from the co-rotating block (equal touch times), the right vertex
// starts one ulp (2^-53 m) further right; its end is unchanged. That adds (1 - s) (2^-53, 0) to
// its offset from a, so f changes by -(e_y(s)) (1 - s) 2^-53 < 0 on (0, 1) (the turning edge
// has e_y > 0): the right vertex touches strictly later, by about e_y (1 - s) 2^-53 / f'(s) =
// 2^-13 · 2^-1 · 2^-53 / 2^-8 = 2^-59 ≈ 1.7e-18 (1.7e-22 s): a 64th of an ulp of s ≈ 1/2.
// The correctly rounded s values (Exact's) tie, and Filtered's, within 2^-44 s, say nothing
// at this scale: only the exact comparison orders the two vertices. Float's rounded values
// tie or mis-order them.
BOOST_AUTO_TEST_CASE(spinning_block_vertices_below_double_resolution) {
  const NodeEdgeMotion left = spinning_vertex({-0.5, -gap}, spin_cos, spin_sin);
  const NodeEdgeMotion right_base = spinning_vertex({0.5, -gap}, spin_cos, spin_sin);
  NodeEdgeMotion right = right_base;
  right.node.start.x = std::nextafter(0.5, 1.0);
  const ReferenceTouch ref_left = reference_first_touch(left), ref_right = reference_first_touch(right);
  BOOST_TEST_REQUIRE((ref_left.status == ReferenceTouch::touch && ref_right.status == ReferenceTouch::touch));
  BOOST_TEST_REQUIRE((reference_order(ref_left, ref_right) == std::optional<Sign>(Sign::negative)));
  const double ds = Q(ref_right.lo - ref_left.lo).get_d();
  BOOST_TEST_MESSAGE("vertices below double resolution: Δs = " << ds << " (ulp of s: "
                                                               << ulp_above(ref_left.lo.get_d()) << ")");
  BOOST_TEST(ds < 0.1 * ulp_above(0.5));
  const auto el = rk::first_touch<rk::Exact>(left), er = rk::first_touch<rk::Exact>(right);
  BOOST_TEST_REQUIRE((el.has_value() && er.has_value()));
  BOOST_TEST(el->s == er->s);  // the correctly rounded values tie ...
  for_policies<rk::Filtered, rk::Exact, rk::Checked>([&](auto policy) {
    using P = decltype(policy);
    expect_order<P>(left, right, Sign::negative);  // ... the exact comparison does not
    BOOST_TEST(earliest<P>({right, left}) == 1);
  });
  const auto fl = rk::first_touch<rk::Float>(left), fr = rk::first_touch<rk::Float>(right);
  BOOST_TEST_REQUIRE((fl.has_value() && fr.has_value()));
  BOOST_TEST_MESSAGE("Float: s_left = " << fl->s << ", s_right = " << fr->s);
  BOOST_TEST(rk::compare_touch<rk::Float>(left, *fl, right, *fr) != Sign::negative);
  BOOST_TEST(earliest<rk::Float>({right, left}) == 0);  // the wrong vertex
}

// Equal exact touch times compare equal: the co-rotating block's two top vertices (the
// construction above), and a motion against its mirror image (x -> -x, exact, with a and b
// swapped so the target stays on the left: f is unchanged, λ becomes 1 - λ).
BOOST_AUTO_TEST_CASE(equal_touch_times_compare_zero) {
  const NodeEdgeMotion left = spinning_vertex({-0.5, -gap}, spin_cos, spin_sin);
  const NodeEdgeMotion right = spinning_vertex({0.5, -gap}, spin_cos, spin_sin);
  const auto mirror = [](Point2 p) { return Point2{-p.x, p.y}; };
  const NodeEdgeMotion m = rotating_edge(0.1, -0.2, 1.0);
  const NodeEdgeMotion mirrored = motion(mirror(m.node.start), mirror(m.node.end), mirror(m.b.start),
                                         mirror(m.b.end), mirror(m.a.start), mirror(m.a.end));
  const ReferenceTouch ref_left = reference_first_touch(left), ref_right = reference_first_touch(right);
  BOOST_TEST_REQUIRE((ref_left.status == ReferenceTouch::touch && ref_right.status == ReferenceTouch::touch));
  BOOST_TEST((ref_left.lo == ref_right.lo && ref_left.hi == ref_right.hi));  // the same f
  for_policies<rk::Filtered, rk::Exact, rk::Checked>([&](auto policy) {
    using P = decltype(policy);
    expect_order<P>(left, right, Sign::zero);
    expect_order<P>(m, mirrored, Sign::zero);
    expect_order<P>(m, m, Sign::zero);
    const auto t = rk::first_touch<P>(m), tm = rk::first_touch<P>(mirrored);
    BOOST_TEST(std::fabs(t->lambda + tm->lambda - 1.0) <= 2 * rk::touch_time_tolerance + 4 * u);
  });
}

// ---------------------------------------------------------------------------------------------
// 4. Filtered against Exact.

namespace {

// Filtered, Exact and Checked on one motion: the same decisions; s and λ within Filtered's
// certified bound plus Exact's rounding (2^-44 + 2^-53, relative on s, absolute on λ: so within
// 1e-12) of Exact's correctly rounded values; Checked returns Filtered's result. Returns
// Exact's touch.
std::optional<TouchTime> agree(const NodeEdgeMotion& m) {
  const auto exact = rk::first_touch<rk::Exact>(m);
  const auto filtered = rk::first_touch<rk::Filtered>(m);
  std::optional<TouchTime> checked;
  BOOST_CHECK_NO_THROW(checked = rk::first_touch<rk::Checked>(m));
  BOOST_TEST_REQUIRE(filtered.has_value() == exact.has_value());
  BOOST_TEST_REQUIRE(checked.has_value() == exact.has_value());
  if (!exact) return exact;
  BOOST_TEST(filtered->root == exact->root);
  // |s_F - s| <= 2^-44 s and |s_E - s| <= u s.
  BOOST_TEST(std::fabs(filtered->s - exact->s) <= (rk::touch_time_tolerance + u) * exact->s * (1 + 4 * u));
  BOOST_TEST(std::fabs(filtered->lambda - exact->lambda) <= rk::touch_time_tolerance + u);
  BOOST_TEST(
      (checked->s == filtered->s && checked->lambda == filtered->lambda && checked->root == filtered->root));
  return exact;
}

// Exact against the rational reference: the same existence, and s, λ correctly rounded.
// Returns the reference (undecided ones are counted and skipped: end-point grazes).
ReferenceTouch against_reference(const NodeEdgeMotion& m, const std::optional<TouchTime>& exact) {
  const ReferenceTouch ref = reference_first_touch(m);
  if (ref.status == ReferenceTouch::undecided) return ref;
  BOOST_TEST_REQUIRE(exact.has_value() == (ref.status == ReferenceTouch::touch));
  if (exact) {
    BOOST_TEST(distance(exact->s, ref) <= half_ulp(exact->s) + Q(0x1p-110));
    BOOST_TEST(lambda_distance(exact->lambda, m, ref) <= half_ulp(exact->lambda) + Q(0x1p-100));
  }
  return ref;
}

struct Touch {
  NodeEdgeMotion motion;
  TouchTime filtered, exact;
  ReferenceTouch reference;
};

// compare_touch under Filtered, Exact and Checked on a pair of touches: one sign, antisymmetric,
// equal to the reference's order where the brackets decide it.
void compare_pair(const Touch& x, const Touch& y) {
  const Sign exact = rk::compare_touch<rk::Exact>(x.motion, x.exact, y.motion, y.exact);
  const Sign filtered = rk::compare_touch<rk::Filtered>(x.motion, x.filtered, y.motion, y.filtered);
  Sign checked = Sign::zero;
  BOOST_CHECK_NO_THROW(checked = rk::compare_touch<rk::Checked>(x.motion, x.filtered, y.motion, y.filtered));
  BOOST_TEST(filtered == exact);
  BOOST_TEST(checked == exact);
  BOOST_TEST(rk::compare_touch<rk::Filtered>(y.motion, y.filtered, x.motion, x.filtered) == -exact);
  if (x.reference.status == ReferenceTouch::touch && y.reference.status == ReferenceTouch::touch) {
    if (const auto order = reference_order(x.reference, y.reference)) BOOST_TEST(exact == *order);
  }
}

void compare_pairs(const std::vector<Touch>& touches, std::mt19937_64& rng, int pairs) {
  if (touches.size() < 2) return;
  std::uniform_int_distribution<std::size_t> pick(0, touches.size() - 1);
  for (int i = 0; i < pairs; ++i) compare_pair(touches[pick(rng)], touches[pick(rng)]);
}

Point2 uniform_point(std::mt19937_64& rng, double half_width, Point2 offset) {
  std::uniform_real_distribution<double> d(-half_width, half_width);
  return {offset.x + d(rng), offset.y + d(rng)};
}

// A node crossing the neighbourhood of a moving edge: it starts right of the edge's line at
// a position along it in [-0.3, 1.3] and ends left of it, while the edge's ends move by up to
// `wobble` times its length (turning and stretching it). `scale` sizes the scene and `offset`
// places it (1e6 m: far from the origin, where the coordinates' common digits cancel).
NodeEdgeMotion random_crossing(std::mt19937_64& rng, double scale, Point2 offset, double wobble) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Point2 a0 = uniform_point(rng, scale, offset);
  const double heading = 6.283185307179586 * unit(rng), length = scale * (0.1 + unit(rng));
  const Point2 b0{a0.x + length * std::cos(heading), a0.y + length * std::sin(heading)};
  const Point2 t{std::cos(heading), std::sin(heading)}, n{-t.y, t.x};  // n: into the target
  const auto along = [&](Point2 base, double l, double h) {
    return Point2{base.x + l * length * t.x + h * length * n.x, base.y + l * length * t.y + h * length * n.y};
  };
  const Point2 p0 = along(a0, -0.3 + 1.6 * unit(rng), -0.5 * unit(rng));
  const Point2 p1 = along(a0, -0.3 + 1.6 * unit(rng), 0.5 * unit(rng));
  const Point2 a1 = uniform_point(rng, wobble * length, a0);
  const Point2 b1 = uniform_point(rng, wobble * length, b0);
  return motion(p0, p1, a0, a1, b0, b1);
}

// A dyadic double with `bits` bits after the binary point, in [-range, range].
double dyadic(std::mt19937_64& rng, double range, int bits) {
  std::uniform_real_distribution<double> d(-range, range);
  return std::ldexp(std::round(std::ldexp(d(rng), bits)), -bits);
}

Point2 dyadic_point(std::mt19937_64& rng, double range, int bits) {
  return {dyadic(rng, range, bits), dyadic(rng, range, bits)};
}

Point2 plus(Point2 p, Point2 q) { return {p.x + q.x, p.y + q.y}; }
Point2 minus(Point2 p, Point2 q) { return {p.x - q.x, p.y - q.y}; }

}  // namespace

BOOST_AUTO_TEST_CASE(filtered_agrees_with_exact_on_random_motions) {
  std::mt19937_64 rng(seed_for("filtered_agrees_with_exact_on_random_motions", 20240603));
  std::vector<Touch> touches;
  int cases = 0, found = 0, undecided = 0, float_differs = 0;
  const Point2 origin{0.0, 0.0}, far{1e6, -1e6};
  for (int i = 0; i < 3000; ++i) {
    const double scale = std::pow(10.0, -3 + (i % 4));  // 1 mm .. 1 m
    const double wobble = (i % 3 == 0) ? 0.0 : 0.5 * std::ldexp(1.0, -(i % 7) * 4);
    const NodeEdgeMotion m = random_crossing(rng, scale, (i % 5 == 4) ? far : origin, wobble);
    // Its near twin: the node's end one ulp away, a touch time ~1e-16 relative apart.
    NodeEdgeMotion twin = m;
    twin.node.end.y = std::nextafter(twin.node.end.y, 1e300);
    for (const NodeEdgeMotion& x : {m, twin}) {
      ++cases;
      const auto exact = agree(x);
      const ReferenceTouch ref = against_reference(x, exact);
      undecided += ref.status == ReferenceTouch::undecided;
      const auto plain = rk::first_touch<rk::Float>(x);
      float_differs += plain.has_value() != exact.has_value() ||
                       (plain && std::fabs(plain->s - exact->s) > 1e-12 * exact->s);
      if (!exact) continue;
      ++found;
      touches.push_back({x, *rk::first_touch<rk::Filtered>(x), *exact, ref});
    }
  }
  BOOST_TEST_MESSAGE(cases << " random motions: " << found << " touches, " << undecided
                           << " undecided by the reference, Float differs (existence or s beyond 1e-12) on "
                           << float_differs);
  BOOST_TEST(found > cases / 4);  // the generator does produce touches
  compare_pairs(touches, rng, 3000);
  // Twins side by side: touch times an ulp of a coordinate apart, where the root enclosures
  // may overlap.
  int twins = 0;
  for (std::size_t i = 0; i + 1 < touches.size(); ++i) {
    if (touches[i + 1].motion.node.start == touches[i].motion.node.start) {
      ++twins;
      compare_pair(touches[i], touches[i + 1]);
    }
  }
  BOOST_TEST_MESSAGE(twins << " twin pairs compared");
}

// Near-degenerate families on dyadic coordinates (so that the degeneracy is exact):
//   through an end: p(1/2) = a(1/2) (or b(1/2)) exactly, r0 = p0 - a0 and dr = -2 r0;
//   A = 0: the edge translating (de = 0), or the node moving with it plus a multiple of its
//          turn (dr = k de);
//   D = 0: the rotating-edge family f = y + k s - s² with y = -k²/4, turned by a multiple of 90°,
//          scaled by a power of two and translated (exact), and the same 2^-50 off.
BOOST_AUTO_TEST_CASE(filtered_agrees_with_exact_on_degenerate_motions) {
  std::mt19937_64 rng(seed_for("filtered_agrees_with_exact_on_degenerate_motions", 77));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Touch> touches;
  int cases = 0, found = 0, at_end = 0, grazes = 0;
  const auto run = [&](const NodeEdgeMotion& m) {
    ++cases;
    const auto exact = agree(m);
    const ReferenceTouch ref = against_reference(m, exact);
    if (!exact) return exact;
    ++found;
    touches.push_back({m, *rk::first_touch<rk::Filtered>(m), *exact, ref});
    return exact;
  };
  for (int i = 0; i < 400; ++i) {
    // Through an end.
    const Point2 a0 = dyadic_point(rng, 1.0, 20), a1 = plus(a0, dyadic_point(rng, 0.25, 20));
    const Point2 b0 = dyadic_point(rng, 1.0, 20), b1 = plus(b0, dyadic_point(rng, 0.25, 20));
    const Point2 r0 = dyadic_point(rng, 0.5, 20);
    const bool through_b = i % 2 == 1;
    const Point2 end0 = through_b ? b0 : a0, end1 = through_b ? b1 : a1;
    const NodeEdgeMotion m = motion(plus(end0, r0), minus(end1, r0), a0, a1, b0, b1);
    if (const auto t = run(m); t && t->s == 0.5) {
      ++at_end;
      BOOST_TEST(t->lambda == (through_b ? 1.0 : 0.0));
    }
    // A = 0.
    const Point2 d = dyadic_point(rng, 0.25, 20);
    run(motion(dyadic_point(rng, 1.0, 20), dyadic_point(rng, 1.0, 20), a0, plus(a0, d), b0, plus(b0, d)));
    const Point2 de = minus(minus(b1, b0), minus(a1, a0));
    const double k = dyadic(rng, 2.0, 4);
    const Point2 p0 = dyadic_point(rng, 1.0, 20);
    run(motion(p0, plus(plus(p0, minus(a1, a0)), {k * de.x, k * de.y}), a0, a1, b0, b1));
    // D = 0, and 2^-50 either side.
    const double slope = std::ldexp(std::round(std::ldexp(0.1 + 1.8 * unit(rng), 10)), -10);  // k in (0, 2)
    const double x = dyadic(rng, 1.0, 10);
    const int turns = static_cast<int>(rng() % 4);
    const double factor = std::ldexp(1.0, static_cast<int>(rng() % 9) - 4);
    const Point2 offset = dyadic_point(rng, 8.0, 10);
    const auto place = [&](Point2 p) {
      for (int q = 0; q < turns; ++q) p = {-p.y, p.x};
      return Point2{offset.x + factor * p.x, offset.y + factor * p.y};
    };
    for (const double nudge : {0.0, 0x1p-50, -0x1p-50}) {
      const NodeEdgeMotion r = rotating_edge(x, -slope * slope / 4 + nudge, slope);
      const auto t = run(motion(place(r.node.start), place(r.node.end), place(r.a.start), place(r.a.end),
                                place(r.b.start), place(r.b.end)));
      if (nudge == 0.0 && t) {
        ++grazes;
        BOOST_TEST(t->s == slope / 2);  // the double root k/2, a dyadic: rounded exactly
      }
    }
  }
  BOOST_TEST_MESSAGE(cases << " degenerate motions: " << found << " touches, " << at_end
                           << " exactly at an edge's end, " << grazes << " grazes");
  BOOST_TEST(at_end > 0);
  BOOST_TEST(grazes > 0);
  compare_pairs(touches, rng, 3000);
}

// The rounded s and λ do not depend on the caller's rounding mode (touch_time.hpp): the same
// bits under upward rounding as under round to nearest.
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_the_rounding_mode) {
  std::mt19937_64 rng(seed_for("results_do_not_depend_on_the_rounding_mode", 5));
  for (int i = 0; i < 300; ++i) {
    const NodeEdgeMotion m = random_crossing(rng, 1.0, {0.0, 0.0}, 0.25);
    for_policies<rk::Filtered, rk::Exact>([&](auto policy) {
      using P = decltype(policy);
      const auto nearest = rk::first_touch<P>(m);
      std::fesetround(FE_UPWARD);
      const auto upward = rk::first_touch<P>(m);
      std::fesetround(FE_TONEAREST);
      BOOST_TEST_REQUIRE(nearest.has_value() == upward.has_value());
      if (nearest) BOOST_TEST((nearest->s == upward->s && nearest->lambda == upward->lambda));
    });
  }
}
