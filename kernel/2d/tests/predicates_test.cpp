#define BOOST_TEST_MODULE kernel_predicates
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/seed.hpp"

// Predicates (cross_sign, orientation, crossing_side) under Float, Filtered and Exact against an
// exact evaluation written here in GMP rationals. Every double is the exact rational it denotes,
// so the reference signs are exact. Filtered and Exact must agree with the reference on every
// input; Float is only counted, per input family.
//
// The reference for crossing_side does not reuse the library's D A + N B formula: it constructs
// the crossing point X of lines a and b exactly and takes the sign of d3 x (X - c.p).
//
// Random tests print their seed; set ROCKCONTACT_TEST_SEED to rerun with another one.

#include <gmpxx.h>

#include <array>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/predicates.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::kernel {
std::ostream& operator<<(std::ostream& out, Sign s) { return out << static_cast<int>(s); }
}  // namespace rockcontact::kernel

namespace rk = rockcontact::kernel;
namespace rkd = rockcontact::kernel::detail;
using rk::Line;
using rk::Point2;
using rk::Sign;

namespace {

using rockcontact::testing::seed_for;

constexpr double u = rockcontact::testing::unit_roundoff;
// The filters' per-operation error bound, valid under every rounding mode (predicates.hpp).
constexpr double eps = 2 * u;

// The rounding modes the filters' bounds are re-derived under: round to nearest, the mode the
// library runs them in, and upward, since the bounds take a whole ulp per operation and so hold
// in any mode as long as nothing overflows (predicates.hpp).
constexpr std::array<int, 2> rounding_modes{FE_TONEAREST, FE_UPWARD};
const char* mode_name(int mode) { return mode == FE_UPWARD ? "upward" : "to nearest"; }

// Does double arithmetic round upward now? (CGAL switches the SSE rounding mode alone, which
// std::fegetround, reading the x87 control word, does not see on x86-64.)
bool rounding_upward() {
  volatile double tiny = 0x1p-60;
  return 1.0 + tiny > 1.0;
}

// Calls f() with the FPU rounding in `mode`. f must be a call the compiler cannot evaluate
// before the switch: the helpers below are noinline and read their inputs from memory.
template <class F>
auto under_rounding(int mode, F&& f) {
  const int previous = std::fegetround();
  std::fesetround(mode);
  const auto result = f();
  std::fesetround(previous);
  return result;
}

Sign sign(const mpq_class& x) { return static_cast<Sign>(sgn(x)); }

mpq_class exact_cross(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  const mpq_class ux = mpq_class(p1.x) - mpq_class(p0.x), uy = mpq_class(p1.y) - mpq_class(p0.y);
  const mpq_class vx = mpq_class(q1.x) - mpq_class(q0.x), vy = mpq_class(q1.y) - mpq_class(q0.y);
  return mpq_class(ux * vy - uy * vx);
}

struct ExactPoint {
  mpq_class x, y;
};

// The crossing of lines a and b, exactly. Precondition: not parallel.
ExactPoint exact_crossing(const Line& a, const Line& b) {
  const mpq_class d1x = mpq_class(a.q.x) - a.p.x, d1y = mpq_class(a.q.y) - a.p.y;
  const mpq_class d2x = mpq_class(b.q.x) - b.p.x, d2y = mpq_class(b.q.y) - b.p.y;
  const mpq_class wx = mpq_class(b.p.x) - a.p.x, wy = mpq_class(b.p.y) - a.p.y;
  const mpq_class s = (wx * d2y - wy * d2x) / (d1x * d2y - d1y * d2x);
  return {mpq_class(a.p.x + s * d1x), mpq_class(a.p.y + s * d1y)};
}

Sign exact_crossing_side(const Line& a, const Line& b, const Line& c) {
  const ExactPoint x = exact_crossing(a, b);
  const mpq_class d3x = mpq_class(c.q.x) - c.p.x, d3y = mpq_class(c.q.y) - c.p.y;
  return sign(mpq_class(d3x * (x.y - c.p.y) - d3y * (x.x - c.p.x)));
}

// Nearest double to an exact rational (ties to either neighbour: only used to build inputs).
double nearest(const mpq_class& x) {
  const double t = x.get_d();  // truncates toward zero
  const double away = std::nextafter(t, sgn(x) >= 0 ? HUGE_VAL : -HUGE_VAL);
  return abs(mpq_class(x - away)) < abs(mpq_class(x - t)) ? away : t;
}

Point2 add(Point2 p, Point2 offset) { return {p.x + offset.x, p.y + offset.y}; }
Point2 scale(Point2 p, double s) { return {p.x * s, p.y * s}; }

bool parallel(const Line& a, const Line& b) { return sgn(exact_cross(a.p, a.q, b.p, b.q)) == 0; }

// Input families for the degree-2 predicate, as four points (p0, p1, q0, q1) of
// (p1 - p0) x (q1 - q0). Orientation inputs are the special case q0 = p0.
struct CrossInput {
  Point2 p0, p1, q0, q1;
};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  Point2 point(double r) { return {uniform(-r, r), uniform(-r, r)}; }
  // A dyadic point: multiples of 2^-10 in [-4, 4], exact under the small integer arithmetic
  // used below.
  Point2 dyadic() { return {integer(-4096, 4096) * 0x1p-10, integer(-4096, 4096) * 0x1p-10}; }

  // r on the line p q (rounded), then moved by k * step in each coordinate, k in [-2, 2].
  Point2 near_line(const Point2& p, const Point2& q, double step) {
    const double t = uniform(-1.0, 2.0);
    return {p.x + t * (q.x - p.x) + integer(-2, 2) * step, p.y + t * (q.y - p.y) + integer(-2, 2) * step};
  }
  // r on the line p q rounded to the nearest double, then moved by k ulps, k in [-2, 2].
  Point2 near_line_ulps(const Point2& p, const Point2& q) {
    const double t = uniform(-1.0, 2.0);
    Point2 r{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    for (int k = integer(-2, 2); k != 0; k += k > 0 ? -1 : 1) r.x = std::nextafter(r.x, k > 0 ? HUGE_VAL : -HUGE_VAL);
    for (int k = integer(-2, 2); k != 0; k += k > 0 ? -1 : 1) r.y = std::nextafter(r.y, k > 0 ? HUGE_VAL : -HUGE_VAL);
    return r;
  }
  // Two points about 1e6 m from the origin on nearly opposite sides, and a rounded point of
  // their line between them (a few hundred metres from the origin): the classic case where
  // double orientation answers at random.
  std::array<Point2, 3> far_line() {
    const double theta = uniform(0.0, 6.283185307179586);
    const double r0 = uniform(0.5e6, 1.5e6), r1 = uniform(0.5e6, 1.5e6);
    const Point2 p{r0 * std::cos(theta), r0 * std::sin(theta)};
    const Point2 q{-r1 * std::cos(theta + 1e-3), -r1 * std::sin(theta + 1e-3)};
    const double t = r0 / (r0 + r1) + uniform(-1e-7, 1e-7);
    return {p, q, Point2{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)}};
  }

 private:
  std::mt19937_64 rng_;
};

std::map<std::string, std::vector<CrossInput>> orientation_families(Generator& g, int count) {
  std::map<std::string, std::vector<CrossInput>> f;
  const auto orient = [](Point2 p, Point2 q, Point2 r) { return CrossInput{p, q, p, r}; };
  const Point2 offset{1e6, -1e6};
  for (int i = 0; i < count; ++i) {
    const Point2 p = g.point(1.0), q = g.point(1.0);
    f["random"].push_back(orient(p, q, g.point(1.0)));
    f["collinear_perturbed_2^-45"].push_back(orient(p, q, g.near_line(p, q, 0x1p-45)));
    f["collinear_perturbed_ulps"].push_back(orient(p, q, g.near_line_ulps(p, q)));
    const auto far = g.far_line();
    f["far_line_1e6"].push_back(orient(far[0], far[1], far[2]));
    f["far_line_1e6_rotated_arguments"].push_back(orient(far[2], far[0], far[1]));
    const Point2 r = g.near_line(p, q, 0x1p-45);
    // Near-degenerate at 1e6 from the origin: the line through the moved points, and a point
    // of it rounded at that magnitude (moving a near-degenerate triple would round it away).
    const Point2 po = add(p, offset), qo = add(q, offset);
    f["offset_1e6_collinear_perturbed_ulps"].push_back(orient(po, qo, g.near_line_ulps(po, qo)));
    f["offset_1e6_random"].push_back(orient(add(p, offset), add(q, offset), add(g.point(1.0), offset)));
    // Exactly collinear: p + m d, p + n d with dyadic p, d and small integers: zero.
    const Point2 o = g.dyadic(), d = g.dyadic();
    const int m = g.integer(1, 7), n = g.integer(-7, 7);
    f["exactly_collinear_dyadic"].push_back(orient(o, {o.x + m * d.x, o.y + m * d.y}, {o.x + n * d.x, o.y + n * d.y}));
    // Axis-aligned collinear: the filter's exact-zero shortcut.
    f["axis_aligned_collinear"].push_back(orient({p.x, p.y}, {p.x, q.y}, {p.x, r.y}));
    // Products below the smallest normal double (coordinates ~1e-163): the underflow term.
    f["underflow_2^-540"].push_back(orient(scale(p, 0x1p-540), scale(q, 0x1p-540), scale(r, 0x1p-540)));
    // Products above the largest double (coordinates ~1e159): the filter must not trust inf.
    f["overflow_2^530"].push_back(orient(scale(p, 0x1p530), scale(q, 0x1p530), scale(r, 0x1p530)));
  }
  return f;
}

std::map<std::string, std::vector<CrossInput>> cross_families(Generator& g, int count) {
  std::map<std::string, std::vector<CrossInput>> f;
  for (int i = 0; i < count; ++i) {
    const Point2 p0 = g.point(1.0), p1 = g.point(1.0), q0 = g.point(1.0);
    f["random"].push_back({p0, p1, q0, g.point(1.0)});
    // q1 - q0 nearly parallel to p1 - p0 (a derived point b_j - a_i against an edge), off by
    // k 2^-45 in each coordinate.
    const double s = g.uniform(-2.0, 2.0);
    const Point2 q1{q0.x + s * (p1.x - p0.x) + g.integer(-2, 2) * 0x1p-45,
                    q0.y + s * (p1.y - p0.y) + g.integer(-2, 2) * 0x1p-45};
    f["near_parallel_2^-45"].push_back({p0, p1, q0, q1});
    // An edge between points ~1e6 m apart against a nearly parallel one joining rounded points
    // of (almost) the same line.
    const auto far = g.far_line();
    const Point2 r = g.near_line_ulps(far[0], far[2]);
    f["near_parallel_far"].push_back({far[0], far[1], far[2], r});
    const Point2 off{1e6 + 0.1, 1e6 - 0.3};
    const Point2 p0o = add(p0, off), p1o = add(p1, off), q0o = add(q0, off);
    const Point2 q1o{q0o.x + s * (p1o.x - p0o.x), q0o.y + s * (p1o.y - p0o.y)};
    f["offset_1e6_near_parallel"].push_back({p0o, p1o, q0o, q1o});
    f["underflow_2^-540"].push_back({scale(p0, 0x1p-540), scale(p1, 0x1p-540), scale(q0, 0x1p-540), scale(q1, 0x1p-540)});
  }
  return f;
}

template <class Policy>
Sign cross_of(const CrossInput& c) {
  return rk::cross_sign<Policy>(c.p0, c.p1, c.q0, c.q1);
}

// Runs the three policies over the families; returns Float's wrong answers per family.
std::map<std::string, int> check_cross_families(const std::map<std::string, std::vector<CrossInput>>& families,
                                                bool as_orientation) {
  std::map<std::string, int> float_wrong;
  for (const auto& [name, inputs] : families) {
    int wrong_filtered = 0, wrong_exact = 0;
    for (const CrossInput& c : inputs) {
      const Sign expected = sign(exact_cross(c.p0, c.p1, c.q0, c.q1));
      Sign filtered, exact, fl;
      if (as_orientation) {
        filtered = rk::orientation<rk::Filtered>(c.p0, c.p1, c.q1);
        exact = rk::orientation<rk::Exact>(c.p0, c.p1, c.q1);
        fl = rk::orientation<rk::Float>(c.p0, c.p1, c.q1);
      } else {
        filtered = cross_of<rk::Filtered>(c);
        exact = cross_of<rk::Exact>(c);
        fl = cross_of<rk::Float>(c);
      }
      wrong_filtered += filtered != expected;
      wrong_exact += exact != expected;
      float_wrong[name] += fl != expected;
    }
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_filtered == 0);
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_exact == 0);
    BOOST_TEST_MESSAGE((as_orientation ? "orientation" : "cross_sign") << " " << name << ": Float wrong on "
                                                                       << float_wrong[name] << " of "
                                                                       << inputs.size());
  }
  return float_wrong;
}

// crossing_side inputs: three lines, a and b not parallel.
struct SideInput {
  Line a, b, c;
};

std::map<std::string, std::vector<SideInput>> crossing_side_families(Generator& g, int count) {
  std::map<std::string, std::vector<SideInput>> f;
  const Point2 offset{1e6, 1e6 + 0.25};
  while (static_cast<int>(f["random"].size()) < count) {
    const Line a{g.point(1.0), g.point(1.0)}, b{g.point(1.0), g.point(1.0)};
    if (parallel(a, b)) continue;
    f["random"].push_back({a, b, Line{g.point(1.0), g.point(1.0)}});
    // c through the crossing rounded to the nearest double (the side is decided by the
    // rounding alone), and through that point moved by k 2^-45, k in [-2, 2].
    const ExactPoint x = exact_crossing(a, b);
    const Point2 xr{nearest(x.x), nearest(x.y)};
    const Point2 far = g.point(1.0);
    f["c_through_rounded_crossing"].push_back({a, b, Line{xr, far}});
    f["c_through_rounded_crossing_reversed"].push_back({a, b, Line{far, xr}});
    f["c_through_perturbed_crossing_2^-45"].push_back(
        {a, b, Line{{xr.x + g.integer(-2, 2) * 0x1p-45, xr.y + g.integer(-2, 2) * 0x1p-45}, far}});
    const Line ao{add(a.p, offset), add(a.q, offset)}, bo{add(b.p, offset), add(b.q, offset)};
    if (!parallel(ao, bo)) {
      const ExactPoint xo = exact_crossing(ao, bo);
      f["offset_1e6_c_through_rounded_crossing"].push_back(
          {ao, bo, Line{{nearest(xo.x), nearest(xo.y)}, add(far, offset)}});
    }
    // a and b within ~1e-12 rad of parallel: the crossing is far away and ill-conditioned.
    const Point2 d{b.q.x - b.p.x, b.q.y - b.p.y};
    const Line near_b{b.p, {b.p.x + d.x * (1 + 1e-12 * g.integer(1, 9)), b.p.y + d.y}};
    const Line a_parallel{a.p, {a.p.x + d.x, a.p.y + d.y}};
    if (!parallel(a_parallel, near_b)) {
      const ExactPoint y = exact_crossing(a_parallel, near_b);
      const Point2 yr{nearest(y.x), nearest(y.y)};
      f["near_parallel_a_b"].push_back({a_parallel, near_b, Line{yr, g.point(1.0)}});
    }
  }
  return f;
}

template <class Policy>
Sign side_under(const SideInput& s) {
  return rk::crossing_side<Policy>(s.a, s.b, s.c);
}

// Three lines through the point x with dyadic directions, each defined by two exact points
// x - k d and x + m d.
std::array<Line, 3> concurrent_lines(Point2 x) {
  const std::array<Point2, 3> d{{{1.0, 0.5}, {-0.25, 1.0}, {0.75, 0.625}}};
  std::array<Line, 3> lines;
  for (std::size_t i = 0; i < 3; ++i) {
    const double k = 3.0 + static_cast<double>(i), m = 5.0 - static_cast<double>(i);
    lines[i] = Line{{x.x - k * d[i].x, x.y - k * d[i].y}, {x.x + m * d[i].x, x.y + m * d[i].y}};
  }
  return lines;
}

Line transformed(const Line& l, double s, Point2 offset) {
  return {add(scale(l.p, s), offset), add(scale(l.q, s), offset)};
}

}  // namespace

BOOST_AUTO_TEST_CASE(orientation_matches_exact_reference) {
  Generator g(seed_for("orientation_matches_exact_reference", 20240601));
  const auto float_wrong = check_cross_families(orientation_families(g, 2000), true);
  // The far-line family is adversarial by construction: plain double must fail on some of it,
  // otherwise the family does not test what it claims to.
  BOOST_TEST(float_wrong.at("far_line_1e6") > 0);
}

BOOST_AUTO_TEST_CASE(cross_sign_matches_exact_reference) {
  Generator g(seed_for("cross_sign_matches_exact_reference", 20240602));
  const auto float_wrong = check_cross_families(cross_families(g, 2000), false);
  BOOST_TEST(float_wrong.at("near_parallel_far") > 0);
}

// Shewchuk's ccwerrboundA with eps = 2^-52 for u, re-derived under round to nearest and
// upward rounding. With ux = fl(p1.x - p0.x) etc., left = fl(ux vy), right = fl(uy vx): each
// product is the exact one times (1 + d1)(1 + d2)(1 + d3), |di| <= eps in either mode, so
//   |det_exact - (left - right)| <= (3 eps + O(eps^2))(|left| + |right|) <= (3 + 16 eps) eps (...),
// where left - right is the exact difference of the rounded products (checked in GMP). The
// final rounding det = fl(left - right) cannot change its sign, rounding being monotone in
// every mode: so the filter's decision |det| > bound => sign(det) is exact must hold, and is
// checked too. The constant must be exactly (3 + 16 eps) eps; subnormal products add the
// underflow term 2^-1070.
struct CrossQuantities {
  double left, right, det, bound;
};

[[gnu::noinline]] CrossQuantities cross_quantities(const CrossInput& c, bool underflow) {
  const double ux = c.p1.x - c.p0.x, uy = c.p1.y - c.p0.y;
  const double vx = c.q1.x - c.q0.x, vy = c.q1.y - c.q0.y;
  const double left = ux * vy, right = uy * vx;
  return {left, right, left - right,
          rkd::cross_error_factor * (std::fabs(left) + std::fabs(right)) +
              (underflow ? rkd::cross_underflow_term : 0.0)};
}

BOOST_AUTO_TEST_CASE(cross_filter_bound_rederived) {
  BOOST_TEST(mpq_class(rkd::cross_error_factor) == mpq_class((3 + 16 * mpq_class(eps)) * eps));
  BOOST_TEST(rkd::cross_underflow_term == 0x1p-1070);

  Generator g(seed_for("cross_filter_bound_rederived", 20240603));
  auto families = cross_families(g, 3000);
  for (auto& [name, inputs] : orientation_families(g, 3000)) {
    if (name != "overflow_2^530") families["orientation_" + name] = std::move(inputs);
  }
  for (const int mode : rounding_modes) {
    double worst_ratio = 0.0;
    for (const auto& [name, inputs] : families) {
      const bool underflow = name.find("underflow") != std::string::npos;
      int violations = 0, wrong_certified_signs = 0;
      for (const CrossInput& c : inputs) {
        const CrossQuantities q = under_rounding(mode, [&] { return cross_quantities(c, underflow); });
        const mpq_class exact = exact_cross(c.p0, c.p1, c.q0, c.q1);
        const mpq_class error = abs(mpq_class(exact - (mpq_class(q.left) - mpq_class(q.right))));
        violations += error > q.bound;
        if (std::fabs(q.det) > q.bound) wrong_certified_signs += sign(exact) != sign(mpq_class(q.det));
        if (!underflow && q.bound > 0) worst_ratio = std::max(worst_ratio, mpq_class(error / q.bound).get_d());
      }
      BOOST_TEST_INFO("family " << name << ", rounding " << mode_name(mode));
      BOOST_TEST(violations == 0);
      BOOST_TEST_INFO("family " << name << ", rounding " << mode_name(mode));
      BOOST_TEST(wrong_certified_signs == 0);
    }
    BOOST_TEST_MESSAGE("cross filter, rounding " << mode_name(mode)
                                                  << ": largest observed error / bound = " << worst_ratio);
  }
}

// The crossing_side semi-static filter, re-derived on random and near-degenerate inputs under
// round to nearest and upward rounding:
//   |V_exact - V| <= 11 eps T, T = D̄ Ā + N̄ B̄ with X̄ = |x1 y2| + |x2 y1| the magnitude of
//   each rounded cross product (predicates.hpp), whenever every magnitude is at least 2^-400.
// V = fl(D A + N B) is the double evaluation of crossing_side_formula in that rounding mode.
struct SideQuantities {
  double value, D, N, A, B;
};

[[gnu::noinline]] SideQuantities side_quantities(const SideInput& s) {
  const auto magnitude = [](double x1, double y1, double x2, double y2) {
    return std::fabs(x1 * y2) + std::fabs(x2 * y1);
  };
  const Line &a = s.a, &b = s.b, &c = s.c;
  const double d1x = a.q.x - a.p.x, d1y = a.q.y - a.p.y, d2x = b.q.x - b.p.x, d2y = b.q.y - b.p.y;
  const double d3x = c.q.x - c.p.x, d3y = c.q.y - c.p.y, wx = b.p.x - a.p.x, wy = b.p.y - a.p.y;
  const double rx = a.p.x - c.p.x, ry = a.p.y - c.p.y;
  return {rkd::crossing_side_formula<double>(a, b, c, rkd::double_diff), magnitude(d1x, d1y, d2x, d2y),
          magnitude(wx, wy, d2x, d2y), magnitude(d3x, d3y, rx, ry), magnitude(d3x, d3y, d1x, d1y)};
}

BOOST_AUTO_TEST_CASE(crossing_side_filter_bound_rederived) {
  BOOST_TEST(rkd::crossing_side_error_factor == 11 * eps);
  Generator g(seed_for("crossing_side_filter_bound_rederived", 20240604));
  const auto families = crossing_side_families(g, 1500);
  for (const int mode : rounding_modes) {
    int violations = 0, checked = 0;
    for (const auto& [name, inputs] : families) {
      for (const SideInput& s : inputs) {
        const SideQuantities q = under_rounding(mode, [&] { return side_quantities(s); });
        if (!(std::fmin(std::fmin(q.D, q.N), std::fmin(q.A, q.B)) >= 0x1p-400)) continue;
        const mpq_class exact = rkd::crossing_side_formula<mpq_class>(
            s.a, s.b, s.c, [](double x, double y) { return mpq_class(mpq_class(x) - mpq_class(y)); });
        const mpq_class error = abs(mpq_class(exact - q.value));
        violations += error > rkd::crossing_side_error_factor * (q.D * q.A + q.N * q.B);
        ++checked;
      }
    }
    BOOST_TEST_INFO("rounding " << mode_name(mode));
    BOOST_TEST(violations == 0);
    BOOST_TEST(checked > 5000);
    BOOST_TEST_MESSAGE("crossing_side bound, rounding " << mode_name(mode) << ": checked on " << checked << " inputs");
  }
}

// Every filter stage on inputs walked across its own bound. Random families rarely land near a
// filter's threshold, which is where a wrong constant or a forgotten rounding would certify a
// wrong sign. Here each degenerate configuration (r on the line p q, or c through the crossing
// of a and b, both rounded; near the origin and 1e6 m from it) is moved one coordinate by k
// ulps for k = 1..48 and by 2^j ulps for j = 6..30, so |value| / bound sweeps from below 1 to
// far above it; every certificate issued is checked against GMP, and the test requires many
// certificates within a factor 4 of the bound, or it has not tested the threshold at all.
// Each filter runs under round to nearest and upward rounding:
//   cross, static:      |det| > (3 + 16 eps) eps (|left| + |right|) + 2^-1070   (predicates.hpp)
//   crossing_side, semi-static:  |V| > 11 eps T                                (predicates.hpp)
//   and the whole staged predicates (filter, interval, exact).
[[gnu::noinline]] std::optional<Sign> static_filter(const Point2& p, const Point2& q, const Point2& r) {
  return rkd::cross_sign_static_filter(p, q, p, r);
}
[[gnu::noinline]] std::optional<Sign> semi_static_filter(const SideInput& s) {
  return rkd::crossing_side_semi_static(s.a, s.b, s.c);
}

BOOST_AUTO_TEST_CASE(filters_never_certify_a_wrong_sign_near_their_bounds) {
  Generator g(seed_for("filters_never_certify_a_wrong_sign_near_their_bounds", 20261125));
  struct Tally {
    int certified = 0, near_bound = 0, wrong = 0;
    void add(bool certifies, bool right, double ratio) {
      if (!certifies) return;
      ++certified;
      near_bound += ratio <= 4.0;
      wrong += !right;
    }
  };
  std::array<Tally, 2> cross_static, side_semi_static;
  Tally cross_whole, side_whole;
  std::vector<int> steps;
  for (int k = 1; k <= 48; ++k) steps.push_back(k);
  for (int j = 6; j <= 30; ++j) steps.push_back(1 << j);
  const auto moved = [](double x, int ulps) {
    for (int i = 0; i < ulps && ulps <= 48; ++i) x = std::nextafter(x, HUGE_VAL);
    if (ulps > 48) x += ulps * (std::nextafter(x, HUGE_VAL) - x);
    return x;
  };
  for (int trial = 0; trial < 300; ++trial) {
    const Point2 offset = trial % 2 == 0 ? Point2{0, 0} : Point2{1e6, -1e6};
    const Point2 p = add(g.point(1.0), offset), q = add(g.point(1.0), offset);
    const double t = g.uniform(-1.0, 2.0);
    const Point2 r0{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    for (const int k : steps) {
      const Point2 r{moved(r0.x, k), r0.y};
      const Sign expected = sign(exact_cross(p, q, p, r));
      const CrossQuantities nearest =
          under_rounding(FE_TONEAREST, [&] { return cross_quantities({p, q, p, r}, true); });
      const double ratio = std::fabs(nearest.det) / nearest.bound;
      for (std::size_t m = 0; m < rounding_modes.size(); ++m) {
        const auto certified = under_rounding(rounding_modes[m], [&] { return static_filter(p, q, r); });
        cross_static[m].add(certified.has_value(), certified == expected, ratio);
      }
      cross_whole.add(true, rk::orientation<rk::Filtered>(p, q, r) == expected, ratio);
    }
    // Lines a and b through a random point X, c through X's rounding, then c.q moved.
    const Point2 x = add(g.point(1.0), offset);
    const auto through = [&](const Point2& point) {
      const Point2 d = g.point(1.0);
      return Line{{point.x - d.x, point.y - d.y}, {point.x + 0.5 * d.x, point.y + 0.5 * d.y}};
    };
    const Line a = through(x), b = through(x);
    if (parallel(a, b)) continue;
    const ExactPoint cross = exact_crossing(a, b);
    const Line c0 = through({nearest(cross.x), nearest(cross.y)});
    for (const int k : steps) {
      const SideInput s{a, b, {c0.p, {moved(c0.q.x, k), c0.q.y}}};
      const Sign expected = exact_crossing_side(s.a, s.b, s.c) * sign(exact_cross(a.p, a.q, b.p, b.q));
      const SideQuantities nearest = under_rounding(FE_TONEAREST, [&] { return side_quantities(s); });
      const double ratio =
          std::fabs(nearest.value) / (rkd::crossing_side_error_factor * (nearest.D * nearest.A + nearest.N * nearest.B));
      for (std::size_t m = 0; m < rounding_modes.size(); ++m) {
        const auto certified = under_rounding(rounding_modes[m], [&] { return semi_static_filter(s); });
        side_semi_static[m].add(certified.has_value(), certified == expected, ratio);
      }
      side_whole.add(true, rkd::crossing_side_value_sign_staged(s.a, s.b, s.c) == expected, ratio);
    }
  }
  const auto report = [](const std::string& name, const Tally& t, int min_near) {
    BOOST_TEST_INFO(name);
    BOOST_TEST(t.wrong == 0);
    BOOST_TEST_INFO(name << ": certificates within 4x of the bound");
    BOOST_TEST(t.near_bound >= min_near);
    BOOST_TEST_INFO(name << ": certificates");
    BOOST_TEST(t.certified > 0);
    BOOST_TEST_MESSAGE(name << ": " << t.certified << " certified, " << t.near_bound << " within 4x of the bound, "
                            << t.wrong << " wrong");
  };
  for (std::size_t m = 0; m < rounding_modes.size(); ++m) {
    report(std::string("cross static filter, rounding ") + mode_name(rounding_modes[m]), cross_static[m], 100);
    report(std::string("crossing_side semi-static, rounding ") + mode_name(rounding_modes[m]), side_semi_static[m], 100);
  }
  report("cross_sign staged", cross_whole, 100);
  report("crossing_side staged", side_whole, 100);
}

BOOST_AUTO_TEST_CASE(crossing_side_matches_exact_reference) {
  Generator g(seed_for("crossing_side_matches_exact_reference", 20240605));
  for (const auto& [name, inputs] : crossing_side_families(g, 1500)) {
    int wrong_filtered = 0, wrong_exact = 0, wrong_float = 0;
    for (const SideInput& s : inputs) {
      const Sign expected = exact_crossing_side(s.a, s.b, s.c);
      wrong_filtered += side_under<rk::Filtered>(s) != expected;
      wrong_exact += side_under<rk::Exact>(s) != expected;
      wrong_float += side_under<rk::Float>(s) != expected;
    }
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_filtered == 0);
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_exact == 0);
    BOOST_TEST_MESSAGE("crossing_side " << name << ": Float wrong on " << wrong_float << " of " << inputs.size());
  }
}

// Degenerate cases where the crossing lies exactly on the third line: the answer is zero.
BOOST_AUTO_TEST_CASE(crossing_side_zero_on_concurrent_lines) {
  struct Case {
    std::string name;
    std::array<Line, 3> lines;
  };
  std::vector<Case> cases;
  // 1. three lines through the dyadic point (0.375, -1.25);
  cases.push_back({"concurrent_dyadic", concurrent_lines({0.375, -1.25})});
  // 2. the same scaled by 2^-20 and moved by 2^20 (multiples of 2^-23 below 2^21: exact);
  {
    auto l = concurrent_lines({0.375, -1.25});
    for (Line& line : l) line = transformed(line, 0x1p-20, {0x1p20, -0x1p20});
    cases.push_back({"concurrent_dyadic_scaled_offset_2^20", l});
  }
  // 3. a non-dyadic crossing: (0,0)-(3,1) and (1,0)-(1,1) cross at (1, 1/3), which lies on
  //    x + 3y = 2 through (2,0) and (-1,1); then scaled by 3/128 and moved by 2^20 (exact for
  //    these small integers);
  {
    std::array<Line, 3> l{{{{0, 0}, {3, 1}}, {{1, 0}, {1, 1}}, {{2, 0}, {-1, 1}}}};
    cases.push_back({"concurrent_non_dyadic", l});
    for (Line& line : l) line = transformed(line, 3.0 / 128.0, {0x1p20, 0x1p20});
    cases.push_back({"concurrent_non_dyadic_scaled_offset", l});
  }
  // 4. c is one of the two lines itself (defined by other points of it).
  {
    const auto l = concurrent_lines({-0.625, 2.5});
    const Line c{{2 * l[0].p.x - l[0].q.x, 2 * l[0].p.y - l[0].q.y}, l[0].q};
    cases.push_back({"c_is_line_a", {l[0], l[1], c}});
  }
  for (const Case& c : cases) {
    const std::array<std::array<int, 3>, 6> permutations{{{0, 1, 2}, {1, 0, 2}, {0, 2, 1}, {2, 0, 1}, {1, 2, 0}, {2, 1, 0}}};
    for (const auto& p : permutations) {
      const Line &a = c.lines[p[0]], &b = c.lines[p[1]], &third = c.lines[p[2]];
      if (parallel(a, b)) continue;
      BOOST_TEST_INFO(c.name << " permutation " << p[0] << p[1] << p[2]);
      BOOST_TEST_REQUIRE(exact_crossing_side(a, b, third) == Sign::zero);
      BOOST_TEST_INFO(c.name << " permutation " << p[0] << p[1] << p[2]);
      BOOST_TEST((rk::crossing_side<rk::Filtered>(a, b, third) == Sign::zero));
      BOOST_TEST_INFO(c.name << " permutation " << p[0] << p[1] << p[2]);
      BOOST_TEST((rk::crossing_side<rk::Exact>(a, b, third) == Sign::zero));
    }
  }
}

BOOST_AUTO_TEST_CASE(counters_count_calls_and_fallbacks) {
  using rk::PredicateKind;
  const auto cross = static_cast<std::size_t>(PredicateKind::cross);
  const auto side = static_cast<std::size_t>(PredicateKind::crossing_side);
  const std::uint64_t n = 100;
  const Point2 p{0.1, 0.2}, q{0.7, -0.3};
  const Point2 well_separated{0.4, 0.9};  // |det| ~ 0.4, far above the bound ~1e-16
  // Exactly collinear points whose products round (0.1 and 0.7 have full 53-bit significands;
  // c = 2 b exactly): fl(det) is zero but the bound is not, and the interval of a rounded
  // product is not a point, so only the exact stage can certify the zero.
  const Point2 a{0.0, 0.0}, b{0.1, 0.7}, c{0.2, 1.4};
  // Exactly collinear dyadic points: every difference and product is exact in double, so the
  // interval stage computes the point interval [0, 0] and settles the zero without Mpzf.
  const Point2 da{0.375, 0.125}, db{0.875, 0.375}, dc{1.625, 0.75};

  rk::reset_predicate_counters();
  for (std::uint64_t i = 0; i < n; ++i) BOOST_TEST((rk::orientation<rk::Filtered>(p, q, well_separated) == Sign::positive));
  auto counted = rk::predicate_counters();
#if ROCKCONTACT_PREDICATE_STATS
  BOOST_TEST(counted.calls[cross] == n);
  BOOST_TEST(counted.interval_fallbacks[cross] == 0u);
  BOOST_TEST(counted.fallbacks[cross] == 0u);

  rk::reset_predicate_counters();
  for (std::uint64_t i = 0; i < n; ++i) BOOST_TEST((rk::orientation<rk::Filtered>(a, b, c) == Sign::zero));
  counted = rk::predicate_counters();
  BOOST_TEST(counted.calls[cross] == n);
  BOOST_TEST(counted.interval_fallbacks[cross] == n);
  BOOST_TEST(counted.fallbacks[cross] == n);

  rk::reset_predicate_counters();
  for (std::uint64_t i = 0; i < n; ++i) BOOST_TEST((rk::orientation<rk::Filtered>(da, db, dc) == Sign::zero));
  counted = rk::predicate_counters();
  BOOST_TEST(counted.calls[cross] == n);
  BOOST_TEST(counted.interval_fallbacks[cross] == n);
  BOOST_TEST(counted.fallbacks[cross] == 0u);

  // Axis-aligned collinear: the exact-zero shortcut of the filter, no fallback.
  rk::reset_predicate_counters();
  BOOST_TEST((rk::orientation<rk::Filtered>({0.1, 0.3}, {0.1, 0.7}, {0.1, -5.0}) == Sign::zero));
  BOOST_TEST(rk::predicate_counters().interval_fallbacks[cross] == 0u);

  // crossing_side: one cross call (the sign of D) and one crossing_side call.
  const auto lines = concurrent_lines({0.375, -1.25});
  const Line away{{5.0, 5.0}, {6.0, 7.5}};
  rk::reset_predicate_counters();
  BOOST_TEST((rk::crossing_side<rk::Filtered>(lines[0], lines[1], away) != Sign::zero));
  counted = rk::predicate_counters();
  BOOST_TEST(counted.calls[cross] == 1u);
  BOOST_TEST(counted.calls[side] == 1u);
  BOOST_TEST(counted.total_interval_fallbacks() == 0u);

  // Three dyadic lines through one point: the semi-static filter cannot certify the zero, the
  // interval stage does (exact operations), Mpzf is not needed.
  rk::reset_predicate_counters();
  BOOST_TEST((rk::crossing_side<rk::Filtered>(lines[0], lines[1], lines[2]) == Sign::zero));
  counted = rk::predicate_counters();
  BOOST_TEST(counted.calls[side] == 1u);
  BOOST_TEST(counted.interval_fallbacks[side] == 1u);
  BOOST_TEST(counted.fallbacks[side] == 0u);

  // A crossing on a line collinear with c (a stacked block's side along the side of the block
  // below): c's points are 4 and 1 times (0.1, 0.7), b's 0 and 2 times, all exactly on one
  // line, and their products round, so the semi-static filter cannot certify the zero. The
  // check that b (or a) lies along c settles it before the degree-4 interval and exact stages.
  const Line along{{0.0, 0.0}, {0.2, 1.4}}, c_line{{0.4, 2.8}, {0.1, 0.7}};
  const Line across{{-1.0, 0.33}, {1.3, 0.29}};
  BOOST_TEST_REQUIRE(exact_crossing_side(across, along, c_line) == Sign::zero);
  BOOST_TEST(!rkd::crossing_side_semi_static(across, along, c_line).has_value());
  rk::reset_predicate_counters();
  BOOST_TEST((rk::crossing_side<rk::Filtered>(across, along, c_line) == Sign::zero));
  BOOST_TEST((rk::crossing_side<rk::Filtered>(along, across, c_line) == Sign::zero));
  BOOST_TEST(rk::predicate_counters().interval_fallbacks[side] == 0u);

  // Exact shares the staged evaluation (a sign has one exact value); Float never falls back.
  rk::reset_predicate_counters();
  BOOST_TEST((rk::orientation<rk::Exact>(a, b, c) == Sign::zero));
  static_cast<void>(rk::orientation<rk::Float>(a, b, c));
  static_cast<void>(rk::crossing_side<rk::Float>(lines[0], lines[1], lines[2]));
  counted = rk::predicate_counters();
  BOOST_TEST(counted.calls[cross] == 3u);
  BOOST_TEST(counted.calls[side] == 1u);
  BOOST_TEST(counted.total_fallbacks() == 1u);

  // Difference of snapshots attributes work to a block.
  const auto before = rk::predicate_counters();
  static_cast<void>(rk::orientation<rk::Filtered>(a, b, c));
  const auto spent = rk::predicate_counters() - before;
  BOOST_TEST(spent.total_calls() == 1u);
  BOOST_TEST(spent.total_interval_fallbacks() == 1u);
  BOOST_TEST(spent.total_fallbacks() == 1u);
#else
  BOOST_TEST(counted.total_calls() == 0u);
  static_cast<void>(a);
  static_cast<void>(b);
  static_cast<void>(c);
  static_cast<void>(da);
  static_cast<void>(db);
  static_cast<void>(dc);
  static_cast<void>(cross);
  static_cast<void>(side);
#endif
}

// The rounding mode around the interval stage: a fallback switches to upward rounding for its
// own evaluation and restores round to nearest at once, so the next predicate's filter, and
// any construction after it, run in the mode the compiler assumed. The collinear dyadic points
// need the interval stage (see counters_count_calls_and_fallbacks).
BOOST_AUTO_TEST_CASE(a_fallback_restores_round_to_nearest) {
  const Point2 da{0.375, 0.125}, db{0.875, 0.375}, dc{1.625, 0.75};
  BOOST_TEST_REQUIRE(!rounding_upward());
  BOOST_TEST((rk::orientation<rk::Filtered>(da, db, dc) == Sign::zero));
  BOOST_TEST(!rounding_upward());
}

// Coordinates whose products overflow: the fuzzer's input (2^-975 to 2^911 in one polygon pair,
// robustness_tests/fuzz/regressions) on which the clang build's semi-static filter of
// crossing_side, run under the upward rounding an earlier fallback in the pair had left on,
// certified the wrong sign: its cross products overflowed to -DBL_MAX, not to infinity, and the
// optimiser had rewritten |x| |y| as |x y|, so the magnitude saturated too and passed the
// finiteness check. In round to nearest the overflow is infinite and the filter defers to the
// interval stage; after a fallback every policy but Float must give the exact sign.
BOOST_AUTO_TEST_CASE(crossing_side_with_overflowing_products_is_exact) {
  const Line a{{0x1.4860304328486p-215, -0x1.c3cbfd257e9bep-152}, {0x1.fd2a61eec58ffp+508, 0x1.fef8f5bc0c5edp-356}};
  const Line b{{0x1.43f3f697ea694p-975, 0x1.6c432a6f0a207p+911}, {-0x1.fd2968f5a87b2p-964, -0x1.fba72fcef415bp-1}};
  const Line c{{0x1.000bfef9ba2fp+98, 0x1.221b8bf003a1dp-206}, {0x1.7b125d3da58dp-42, 0x1.f00006020035cp-724}};
  const Sign expected = exact_crossing_side(a, b, c);
  BOOST_TEST_REQUIRE(expected != Sign::zero);
  BOOST_TEST(!semi_static_filter({a, b, c}).has_value());
  // After a fallback, as in the fuzzer's pair: the filter runs in round to nearest again.
  BOOST_TEST((rk::orientation<rk::Filtered>({0.375, 0.125}, {0.875, 0.375}, {1.625, 0.75}) == Sign::zero));
  BOOST_TEST((rk::crossing_side<rk::Filtered>(a, b, c) == expected));
  BOOST_TEST((rk::crossing_side<rk::Exact>(a, b, c) == expected));
  BOOST_TEST((rk::crossing_side<rk::Checked>(a, b, c) == expected));
}

// Checked: the staged and the exact sign agree on every input family (no throw), and a
// disagreement report names the predicate, both signs and the input in hexadecimal floats.
BOOST_AUTO_TEST_CASE(checked_agrees_and_reports_with_full_input) {
  Generator g(seed_for("checked_agrees_and_reports_with_full_input", 20261126));
  std::size_t checked = 0;
  for (const auto& [name, inputs] : cross_families(g, 500)) {
    for (const CrossInput& c : inputs) {
      BOOST_TEST((rk::cross_sign<rk::Checked>(c.p0, c.p1, c.q0, c.q1) == sign(exact_cross(c.p0, c.p1, c.q0, c.q1))));
      ++checked;
    }
  }
  for (const auto& [name, inputs] : crossing_side_families(g, 500)) {
    for (const SideInput& s : inputs) {
      BOOST_TEST((side_under<rk::Checked>(s) == exact_crossing_side(s.a, s.b, s.c)));
      ++checked;
    }
  }
  BOOST_TEST(checked > 5000u);
  try {
    rkd::cross_sign_disagrees({0.1, 0}, {1, 0}, {0, 0}, {0, -0x1p-1074}, Sign::zero, Sign::negative);
    BOOST_FAIL("no PolicyDisagreement thrown");
  } catch (const rk::PolicyDisagreement& e) {
    const std::string what = e.what();
    BOOST_TEST_INFO(what);
    BOOST_TEST(what.find("cross_sign staged sign 0 but exact sign -1") != std::string::npos);
    BOOST_TEST_INFO(what);
    BOOST_TEST(what.find("[0x1.999999999999ap-4, 0x0p+0, 0x1p+0, 0x0p+0, 0x0p+0, 0x0p+0, 0x0p+0, -0x0.0000000000001p-1022]") !=
               std::string::npos);
  }
}
