#define BOOST_TEST_MODULE kernel_crossing_point
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/seed.hpp"

// construct_crossing_point (crossing_point.hpp) against the exact crossing, computed here in
// GMP rationals as the intersection of the two lines by Cramer's rule on the input doubles.
//
// The inputs are what makes the construction hard: a TP segment t0 -> t1 and a line through a
// point of it at an angle log-uniform in [1e-17, 1] rad, both rounded, near the origin and
// 1e6 m from it, plus crossings at a segment's end point and on dyadic grids where the double
// formula is exact. Every case whose exact crossing lies on the segment (the construction's
// precondition) is checked:
//   * the derivation: |s' - s| <= e (N̄ + D̄) / |D'| + u |s'| (+ the underflow terms) for the
//     double parameter s' = fl(N'/D') on every input, certified or not;
//   * stage 1 alone (crossing_in_double): whenever it answers, each coordinate is within
//     (ds + 3u) |d_c| + 2u |X_c| of the exact crossing, ds the certificate it returned;
//   * the policy functions: Filtered within (2^-40 + 3u) |d_c| + 2u |X_c|, and bitwise equal to
//     Exact (the exact crossing rounded to nearest) whenever stage 1 refused; Exact within
//     u |X_c| (a correct rounding).
// Float is measured, not asserted: its worst error in units of |d| shows what the filter buys.

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/crossing_point.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rk = rockcontact::kernel;
namespace rkd = rockcontact::kernel::detail;
using rk::Point2;

namespace {

using rockcontact::testing::seed_for;
constexpr double u = rockcontact::testing::unit_roundoff;

struct Input {
  Point2 p, q, t0, t1;
};

struct ExactCrossing {
  mpq_class s, x, y;
};

ExactCrossing exact_crossing(const Input& in) {
  const mpq_class lx = mpq_class(in.q.x) - in.p.x, ly = mpq_class(in.q.y) - in.p.y;
  const mpq_class dx = mpq_class(in.t1.x) - in.t0.x, dy = mpq_class(in.t1.y) - in.t0.y;
  const mpq_class wx = mpq_class(in.p.x) - in.t0.x, wy = mpq_class(in.p.y) - in.t0.y;
  const mpq_class s = (lx * wy - ly * wx) / (lx * dy - ly * dx);
  return {s, in.t0.x + s * dx, in.t0.y + s * dy};
}

bool parallel(const Input& in) {
  const mpq_class lx = mpq_class(in.q.x) - in.p.x, ly = mpq_class(in.q.y) - in.p.y;
  const mpq_class dx = mpq_class(in.t1.x) - in.t0.x, dy = mpq_class(in.t1.y) - in.t0.y;
  return sgn(lx * dy - ly * dx) == 0;
}

// A line through the point at parameter s of t0 -> t1, at `angle` to it, both rounded.
Input near_parallel(std::mt19937_64& rng, Point2 offset, double angle) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double heading = 6.283185307179586 * unit(rng);
  const double length = 0.05 + 2.0 * unit(rng);
  const Point2 t0{offset.x + unit(rng) - 0.5, offset.y + unit(rng) - 0.5};
  const Point2 t1{t0.x + length * std::cos(heading), t0.y + length * std::sin(heading)};
  const double s = unit(rng);
  const Point2 x{t0.x + s * (t1.x - t0.x), t0.y + s * (t1.y - t0.y)};
  const double turn = heading + (unit(rng) < 0.5 ? angle : -angle);
  const double a = 0.05 + unit(rng), b = 0.05 + unit(rng);
  return {{x.x - a * std::cos(turn), x.y - a * std::sin(turn)}, {x.x + b * std::cos(turn), x.y + b * std::sin(turn)},
          t0, t1};
}

std::vector<Input> inputs(std::mt19937_64& rng) {
  std::vector<Input> out;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Point2 offset : {Point2{0, 0}, Point2{1e6, -1e6}}) {
    for (int k = 0; k < 6000; ++k) out.push_back(near_parallel(rng, offset, std::pow(10.0, -17.0 * unit(rng))));
  }
  // The line through t1 exactly (a crossing at the segment's end, s = 1), nearly parallel.
  for (int k = 0; k < 1000; ++k) {
    Input in = near_parallel(rng, {0, 0}, std::pow(10.0, -15.0 * unit(rng)));
    in.q = in.t1;
    out.push_back(in);
  }
  // Dyadic grid 2^-10 (every difference and product exact at this size): s' is s rounded once.
  for (int k = 0; k < 1000; ++k) {
    const auto grid = [&] { return std::round((unit(rng) - 0.5) * 4096.0) / 1024.0; };
    out.push_back({{grid(), grid()}, {grid(), grid()}, {grid(), grid()}, {grid(), grid()}});
  }
  return out;
}

double to_double(const mpq_class& x) { return x.get_d(); }

}  // namespace

BOOST_AUTO_TEST_CASE(filtered_crossings_meet_their_certified_bound) {
  std::mt19937_64 rng(seed_for("filtered_crossings_meet_their_certified_bound", 20261124));
  const double e = (4.0 + 32.0 * u) * u;  // crossing_point.hpp: Shewchuk's bound plus the final rounding
  int checked = 0, certified = 0, refused = 0, derivation_violations = 0, stage1_violations = 0;
  int filtered_violations = 0, not_exact_after_refusal = 0, exact_violations = 0;
  double worst_float = 0.0, worst_filtered = 0.0;  // max |X' - X| / |d| per coordinate
  for (const Input& in : inputs(rng)) {
    if (parallel(in)) continue;
    const ExactCrossing x = exact_crossing(in);
    if (x.s < 0 || x.s > 1) continue;  // the crossing is not on the segment: outside the contract
    ++checked;
    const double lx = in.q.x - in.p.x, ly = in.q.y - in.p.y, dx = in.t1.x - in.t0.x, dy = in.t1.y - in.t0.y;
    const double wx = in.p.x - in.t0.x, wy = in.p.y - in.t0.y;
    const double n = lx * wy - ly * wx, d = lx * dy - ly * dx;
    const double n_bar = std::fabs(lx * wy) + std::fabs(ly * wx), d_bar = std::fabs(lx * dy) + std::fabs(ly * dx);
    if (d != 0.0) {
      const double s = n / d;
      const mpq_class bound = mpq_class(e * (n_bar + d_bar)) / std::fabs(d) + u * std::fabs(s) + 0x1p-1072;
      derivation_violations += abs(mpq_class(s - x.s)) > bound * (1 + 0x1p-40);
    }
    const auto coordinate_error = [](double computed, const mpq_class& exact) {
      return mpq_class(abs(mpq_class(computed - exact)));
    };
    const auto within = [&](const Point2& point, double ds) {
      const auto ok = [&](double computed, const mpq_class& exact, double dc) {
        const mpq_class bound = (ds + 3 * u) * std::fabs(dc) + 2 * u * abs(exact) + 0x1p-1073;
        return coordinate_error(computed, exact) <= bound * (1 + 0x1p-40);
      };
      return ok(point.x, x.x, dx) && ok(point.y, x.y, dy);
    };
    const auto relative = [&](const Point2& point) {
      const double len = std::hypot(dx, dy);
      return std::max(to_double(coordinate_error(point.x, x.x)), to_double(coordinate_error(point.y, x.y))) / len;
    };

    const auto stage1 = rkd::crossing_in_double(in.p, in.q, in.t0, in.t1, rk::crossing_parameter_tolerance);
    const Point2 filtered = rk::construct_crossing_point<rk::Filtered>(in.p, in.q, in.t0, in.t1);
    const Point2 exact = rk::construct_crossing_point<rk::Exact>(in.p, in.q, in.t0, in.t1);
    if (stage1) {
      ++certified;
      stage1_violations += !within(stage1->point, stage1->parameter_error);
      BOOST_TEST_REQUIRE(stage1->parameter_error <= rk::crossing_parameter_tolerance);
    } else {
      ++refused;
      not_exact_after_refusal += !(filtered == exact);
    }
    filtered_violations += !within(filtered, rk::crossing_parameter_tolerance);
    exact_violations += !(coordinate_error(exact.x, x.x) <= u * abs(x.x) && coordinate_error(exact.y, x.y) <= u * abs(x.y));
    worst_filtered = std::max(worst_filtered, relative(filtered));
    worst_float = std::max(worst_float, relative(rk::construct_crossing_point<rk::Float>(in.p, in.q, in.t0, in.t1)));
  }
  BOOST_TEST(derivation_violations == 0);
  BOOST_TEST(stage1_violations == 0);
  BOOST_TEST(filtered_violations == 0);
  BOOST_TEST(not_exact_after_refusal == 0);
  BOOST_TEST(exact_violations == 0);
  // Both stages must have been exercised, or the inputs do not test what they claim.
  BOOST_TEST(certified > 1000);
  BOOST_TEST(refused > 1000);
  BOOST_TEST_MESSAGE(checked << " crossings: " << certified << " certified in double, " << refused
                             << " rounded exactly; worst error / |d|: Filtered " << worst_filtered
                             << ", Float " << worst_float);
}

// The fallback is counted: one call per construction, one fallback per exact rounding.
BOOST_AUTO_TEST_CASE(fallbacks_are_counted) {
  const auto kind = static_cast<std::size_t>(rk::PredicateKind::crossing_point);
  const rk::PredicateCounters before = rk::predicate_counters();
  // At 90 degrees: certified. The diagonal y = x and a line 2^-30 rad off it, crossing at the
  // origin: D = 2^-28 against products of size 4, so ds ~ 3u 2^31 > 2^-40: refused.
  rk::construct_crossing_point<rk::Filtered>({0, 0}, {1, 1}, {0, 1}, {1, 0});
  rk::construct_crossing_point<rk::Filtered>({-1, -1 + 0x1p-30}, {1, 1 - 0x1p-30}, {-1, -1}, {1, 1});
  const rk::PredicateCounters spent = rk::predicate_counters() - before;
#if ROCKCONTACT_PREDICATE_STATS
  BOOST_TEST(spent.calls[kind] == 2u);
  BOOST_TEST(spent.fallbacks[kind] == 1u);
#else
  BOOST_TEST(spent.calls[kind] == 0u);
#endif
}
