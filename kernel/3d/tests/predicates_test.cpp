#define BOOST_TEST_MODULE kernel3d_predicates
#include <boost/test/unit_test.hpp>

// The triple product ((p1 - p0) x (q1 - q0)) . (r1 - r0) and orient3d under Float, Filtered,
// Exact and Checked against an evaluation written here in GMP rationals (every double is the
// exact rational it denotes, so the reference signs are exact). The staged policies must agree
// with it on every input; Float is only counted. The static filter's bound is re-derived in GMP
// under round to nearest and upward rounding. Random tests print their seed; set
// ROCKCONTACT_TEST_SEED to rerun with another one.

#include <gmpxx.h>

#include <array>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/testing/seed.hpp"

namespace rk = rockcontact::kernel;
namespace rkd = rockcontact::kernel::detail;
using rk::Point3;
using rk::Sign;

namespace {

using rockcontact::testing::seed_for;

struct TripleInput {
  Point3 p0, p1, q0, q1, r0, r1;
};

Sign sign(const mpq_class& x) { return static_cast<Sign>(sgn(x)); }

mpq_class exact_triple(const TripleInput& t) {
  const auto d = [](double a, double b) { return mpq_class(mpq_class(a) - mpq_class(b)); };
  const mpq_class ux = d(t.p1.x, t.p0.x), uy = d(t.p1.y, t.p0.y), uz = d(t.p1.z, t.p0.z);
  const mpq_class vx = d(t.q1.x, t.q0.x), vy = d(t.q1.y, t.q0.y), vz = d(t.q1.z, t.q0.z);
  const mpq_class wx = d(t.r1.x, t.r0.x), wy = d(t.r1.y, t.r0.y), wz = d(t.r1.z, t.r0.z);
  return mpq_class((uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz);
}

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  Point3 point(double r, Point3 offset = {}) {
    return {offset.x + uniform(-r, r), offset.y + uniform(-r, r), offset.z + uniform(-r, r)};
  }
  // A point of the plane through a, b, c (rounded), moved by k ulps in x, k in [-2, 2].
  Point3 near_plane(const Point3& a, const Point3& b, const Point3& c) {
    const double s = uniform(-1.0, 2.0), t = uniform(-1.0, 2.0);
    Point3 p{a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
             a.z + s * (b.z - a.z) + t * (c.z - a.z)};
    for (int k = integer(-2, 2); k != 0; k += k > 0 ? -1 : 1) p.x = std::nextafter(p.x, k > 0 ? HUGE_VAL : -HUGE_VAL);
    return p;
  }
  // A point with coordinates multiple of 2^-10 in [-4, 4]: its products are exact in double.
  Point3 dyadic() {
    return {integer(-4096, 4096) * 0x1p-10, integer(-4096, 4096) * 0x1p-10, integer(-4096, 4096) * 0x1p-10};
  }

 private:
  std::mt19937_64 rng_;
};

// Input families: random, points near a plane (orient3d), near a plane 1e6 m from the origin,
// exactly coplanar dyadic points, and tiny (underflowing) and huge coordinates.
std::map<std::string, std::vector<TripleInput>> families(Generator& g, int n) {
  std::map<std::string, std::vector<TripleInput>> out;
  for (int i = 0; i < n; ++i) {
    out["random"].push_back({g.point(1), g.point(1), g.point(1), g.point(1), g.point(1), g.point(1)});
    const Point3 a = g.point(1), b = g.point(1), c = g.point(1);
    out["near_plane"].push_back({a, b, a, c, a, g.near_plane(a, b, c)});
    const Point3 o{1e6, -1e6, 1e6};
    const Point3 fa = g.point(1, o), fb = g.point(1, o), fc = g.point(1, o);
    out["near_plane_1e6"].push_back({fa, fb, fa, fc, fa, g.near_plane(fa, fb, fc)});
    const Point3 da = g.dyadic(), db = g.dyadic(), dc = g.dyadic();
    const int s = g.integer(-3, 3), t = g.integer(-3, 3);
    const Point3 dd{da.x + s * (db.x - da.x) + t * (dc.x - da.x), da.y + s * (db.y - da.y) + t * (dc.y - da.y),
                    da.z + s * (db.z - da.z) + t * (dc.z - da.z)};
    out["coplanar_dyadic"].push_back({da, db, da, dc, da, dd});
    const double tiny = 0x1p-530;
    out["underflow_2^-530"].push_back({g.point(tiny), g.point(tiny), g.point(tiny), g.point(tiny), g.point(tiny), g.point(tiny)});
    const double huge = 0x1p330;
    out["large_2^330"].push_back({g.point(huge), g.point(huge), g.point(huge), g.point(huge), g.point(huge), g.point(huge)});
  }
  return out;
}

template <class Policy>
Sign triple_under(const TripleInput& t) {
  return rk::triple_sign<Policy>(t.p0, t.p1, t.q0, t.q1, t.r0, t.r1);
}

constexpr std::array<int, 2> rounding_modes{FE_TONEAREST, FE_UPWARD};
const char* mode_name(int mode) { return mode == FE_UPWARD ? "upward" : "to nearest"; }

[[gnu::noinline]] std::optional<Sign> static_filter(const TripleInput& t) {
  return rkd::triple_sign_static_filter(t.p0, t.p1, t.q0, t.q1, t.r0, t.r1);
}

}  // namespace

BOOST_AUTO_TEST_CASE(staged_policies_match_exact_reference) {
  Generator g(seed_for("staged_policies_match_exact_reference", 20261125));
  for (const auto& [name, inputs] : families(g, 2000)) {
    int wrong_filtered = 0, wrong_exact = 0, wrong_checked = 0, wrong_float = 0;
    for (const TripleInput& t : inputs) {
      const Sign expected = sign(exact_triple(t));
      wrong_filtered += triple_under<rk::Filtered>(t) != expected;
      wrong_exact += triple_under<rk::Exact>(t) != expected;
      wrong_checked += triple_under<rk::Checked>(t) != expected;
      wrong_float += triple_under<rk::Float>(t) != expected;
    }
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_filtered == 0);
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_exact == 0);
    BOOST_TEST_INFO("family " << name);
    BOOST_TEST(wrong_checked == 0);
    BOOST_TEST_MESSAGE("triple_sign " << name << ": Float wrong on " << wrong_float << " of " << inputs.size());
  }
}

// TripleSigns (one normal against many point pairs) gives triple_sign's sign under every policy and
// counts the same calls, on every input family: its filter is triple_sign's, computed in the
// same order, so the same inputs reach the interval stage.
BOOST_AUTO_TEST_CASE(triple_signs_equal_triple_sign) {
  Generator g(seed_for("triple_signs_equal_triple_sign", 20261127));
  const auto check = [](const auto policy, const TripleInput& t) {
    using Policy = std::remove_cv_t<decltype(policy)>;
    const rk::TripleSigns<Policy> signs(t.p0, t.p1, t.q0, t.q1);
    const auto before = rk::predicate_counters();
    const Sign batched = signs(t.r0, t.r1);
    [[maybe_unused]] const auto batched_counts = rk::predicate_counters() - before;
    const auto middle = rk::predicate_counters();
    const Sign single = triple_under<Policy>(t);
    [[maybe_unused]] const auto single_counts = rk::predicate_counters() - middle;
    BOOST_TEST((batched == single));
#if ROCKCONTACT_PREDICATE_STATS
    BOOST_TEST((batched_counts.calls == single_counts.calls));
    BOOST_TEST((batched_counts.interval_fallbacks == single_counts.interval_fallbacks));
#endif
  };
  for (const auto& [name, inputs] : families(g, 500)) {
    BOOST_TEST_CONTEXT("family " << name) {
      for (const TripleInput& t : inputs) {
        check(rk::Float{}, t);
        check(rk::Filtered{}, t);
        check(rk::Exact{}, t);
        check(rk::Checked{}, t);
      }
    }
  }
}

// The static filter never certifies a wrong sign, under round to nearest (the library's mode)
// and upward rounding (its eps of a whole ulp holds in any mode barring overflow), and
// it certifies most random inputs. Its constant is exactly 9 eps, eps = 2^-52 (predicates.hpp).
BOOST_AUTO_TEST_CASE(static_filter_rederived_under_both_rounding_modes) {
  BOOST_TEST(rkd::triple_error_factor == 9 * 0x1p-52);
  Generator g(seed_for("static_filter_rederived_under_both_rounding_modes", 20261126));
  const auto inputs = families(g, 3000);
  for (const int mode : rounding_modes) {
    for (const auto& [name, list] : inputs) {
      int wrong = 0, certified = 0;
      for (const TripleInput& t : list) {
        const int previous = std::fegetround();
        std::fesetround(mode);
        const std::optional<Sign> filtered = static_filter(t);
        std::fesetround(previous);
        if (!filtered) continue;
        ++certified;
        wrong += *filtered != sign(exact_triple(t));
      }
      BOOST_TEST_INFO("family " << name << ", rounding " << mode_name(mode));
      BOOST_TEST(wrong == 0);
      if (name == "random") {
        BOOST_TEST_INFO("rounding " << mode_name(mode));
        BOOST_TEST(certified == static_cast<int>(list.size()));
      }
      BOOST_TEST_MESSAGE("static filter, " << name << ", rounding " << mode_name(mode) << ": " << certified
                                           << " of " << list.size() << " certified");
    }
  }
}

// Exactly coplanar dyadic points: the filter cannot certify a zero whose products round, but the
// interval stage computes the point [0, 0] when every operation is exact, so Mpzf is not needed.
BOOST_AUTO_TEST_CASE(coplanar_dyadic_points_end_at_the_interval_stage) {
  const Point3 a{0.375, 0.125, -0.5}, b{0.875, 0.375, 0.25}, c{-0.125, 1.5, 0.75};
  const Point3 d{a.x + 2 * (b.x - a.x) - (c.x - a.x), a.y + 2 * (b.y - a.y) - (c.y - a.y),
                 a.z + 2 * (b.z - a.z) - (c.z - a.z)};
  rk::reset_predicate_counters();
  BOOST_TEST((rk::orient3d<rk::Filtered>(a, b, c, d) == Sign::zero));
  const auto kind = static_cast<std::size_t>(rk::PredicateKind::triple);
  const rk::PredicateCounters counted = rk::predicate_counters();
#if ROCKCONTACT_PREDICATE_STATS
  BOOST_TEST(counted.calls[kind] == 1u);
  BOOST_TEST(counted.interval_fallbacks[kind] == 1u);
  BOOST_TEST(counted.fallbacks[kind] == 0u);
#else
  BOOST_TEST(counted.total_calls() == 0u);
  static_cast<void>(kind);
#endif
}

// parallel: the cross product of two directions is exactly zero, decided per component.
BOOST_AUTO_TEST_CASE(parallel_directions_are_decided_exactly) {
  const Point3 o{0.1, 0.2, 0.3}, p{0.1 + 0.7, 0.2 + 0.7, 0.3 + 0.7};
  // 0.1 + 0.7 rounds, so (p - o) is not exactly (0.7, 0.7, 0.7); compare with a copy of itself.
  BOOST_TEST(rk::parallel<rk::Filtered>(o, p, o, p));
  BOOST_TEST(rk::parallel<rk::Filtered>(o, p, p, o));
  BOOST_TEST(!rk::parallel<rk::Filtered>(o, p, o, Point3{p.x, p.y, std::nextafter(p.z, 2.0)}));
  BOOST_TEST(rk::parallel<rk::Filtered>({0, 0, 0}, {1, 2, 3}, {5, 5, 5}, {7, 9, 11}));
  BOOST_TEST(!rk::parallel<rk::Filtered>({0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}));
}
