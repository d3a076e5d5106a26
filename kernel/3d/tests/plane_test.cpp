#define BOOST_TEST_MODULE kernel3d_plane
#include "rockcontact/kernel/3d/plane.hpp"

#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <array>
#include <cfenv>
#include <cmath>
#include <initializer_list>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "rockcontact/kernel/3d/detail/plane_formulas.hpp"
#include "rockcontact/kernel/3d/detail/running_error.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/testing/seed.hpp"

// The plane predicates against an independent exact oracle written here in GMP rationals
// (the plane's coefficients in absolute coordinates, the three-plane point by Gaussian
// elimination, the side as the sign of n . X - d): random planes of both kinds, exact
// incidences on an integer lattice (every sign zero), the same moved by 2^-40 (signs decided
// by a hair), and far from the origin by 2^20. Filtered, Exact and Checked must match the oracle
// exactly; Float's misses are counted.

namespace rk = rockcontact::kernel;
using rk::Plane3;
using rk::Point3;
using rk::Sign;

namespace {

struct Q3 {
  mpq_class x, y, z;
};

// n . x = d in absolute coordinates.
std::pair<Q3, mpq_class> oracle_plane(const Plane3& p) {
  if (p.kind == Plane3::Kind::coefficients) {
    const auto& c = p.coefficients;
    return {{c[0], c[1], c[2]}, c[3]};
  }
  const auto& [a, b, c] = p.points;
  const Q3 u{mpq_class(b.x) - a.x, mpq_class(b.y) - a.y, mpq_class(b.z) - a.z};
  const Q3 v{mpq_class(c.x) - a.x, mpq_class(c.y) - a.y, mpq_class(c.z) - a.z};
  const Q3 n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  return {n, n.x * a.x + n.y * a.y + n.z * a.z};
}

Sign sign_of(const mpq_class& q) { return q > 0 ? Sign::positive : q < 0 ? Sign::negative : Sign::zero; }

// The meeting point of three planes by Gaussian elimination with a non-zero pivot.
Q3 oracle_point(const Plane3& p, const Plane3& q, const Plane3& r) {
  std::array<std::array<mpq_class, 4>, 3> m;
  const Plane3* planes[] = {&p, &q, &r};
  for (int i = 0; i < 3; ++i) {
    const auto [n, d] = oracle_plane(*planes[i]);
    m[i] = {n.x, n.y, n.z, d};
  }
  for (int col = 0; col < 3; ++col) {
    int pivot = col;
    while (m[pivot][col] == 0) ++pivot;  // the normals are independent
    std::swap(m[col], m[pivot]);
    for (int row = 0; row < 3; ++row) {
      if (row == col || m[row][col] == 0) continue;
      const mpq_class f = m[row][col] / m[col][col];
      for (int k = col; k < 4; ++k) m[row][k] -= f * m[col][k];
    }
  }
  return {m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]};
}

Sign oracle_side(const Plane3& s, const Q3& x) {
  const auto [n, d] = oracle_plane(s);
  return sign_of(n.x * x.x + n.y * x.y + n.z * x.z - d);
}

bool independent(const Plane3& p, const Plane3& q, const Plane3& r) {
  const Q3 a = oracle_plane(p).first, b = oracle_plane(q).first, c = oracle_plane(r).first;
  return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x) != 0;
}

int float_misses = 0;

void check_three_plane(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  const Sign expected = oracle_side(s, oracle_point(p, q, r));
  BOOST_TEST((rk::side_of_plane<rk::Filtered>(s, p, q, r) == expected));
  BOOST_TEST((rk::side_of_plane<rk::Exact>(s, p, q, r) == expected));
  BOOST_TEST((rk::side_of_plane<rk::Checked>(s, p, q, r) == expected));
  float_misses += rk::side_of_plane<rk::Float>(s, p, q, r) != expected;
}

void check_point(const Plane3& s, const Point3& x) {
  const Sign expected = oracle_side(s, {x.x, x.y, x.z});
  BOOST_TEST((rk::side_of_plane<rk::Filtered>(s, x) == expected));
  BOOST_TEST((rk::side_of_plane<rk::Exact>(s, x) == expected));
  BOOST_TEST((rk::side_of_plane<rk::Checked>(s, x) == expected));
  float_misses += rk::side_of_plane<rk::Float>(s, x) != expected;
}

Point3 operator+(Point3 a, Point3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point3 operator-(Point3 a, Point3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

}  // namespace

BOOST_AUTO_TEST_CASE(random_planes) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("random_planes", 20261125));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto point = [&] { return Point3{u(rng), u(rng), u(rng)}; };
  const auto plane = [&] {
    if (rng() % 2 == 0) return Plane3::through(point(), point(), point());
    return Plane3::from_coefficients(u(rng), u(rng), u(rng), u(rng));
  };
  float_misses = 0;
  const auto before = rk::predicate_counters();
  for (int i = 0; i < 2000; ++i) {
    const Plane3 s = plane(), p = plane(), q = plane(), r = plane();
    check_point(s, point());
    if (independent(p, q, r)) check_three_plane(s, p, q, r);
  }
  [[maybe_unused]] const auto spent = rk::predicate_counters() - before;
#if ROCKCONTACT_PREDICATE_STATS
  // The double filters decide random (non-degenerate) cases: fewer than 1% reach the interval
  // stage (counted over Filtered, Exact and Checked's staged calls alike).
  const auto kind = static_cast<std::size_t>(rk::PredicateKind::plane_side);
  BOOST_TEST(spent.calls[kind] > 0u);
  BOOST_TEST(spent.interval_fallbacks[kind] * 100 < spent.calls[kind]);
#endif
  BOOST_TEST_MESSAGE("random planes: Float misses " << float_misses);
}

// Integer lattice: X an integer point (offset by 2^20 in half the cases, still exact); planes
// through three points with centroid X (X + u, X + w, X - u - w), or by integer coefficients
// with d = n . X. Every plane contains X, so every side is zero; then s's first point, or its
// d, moved by 2^-40 (2^-30 at the offset, where 2^-40 is below the coordinates' ulp) decides
// the sign by a hair.
BOOST_AUTO_TEST_CASE(lattice_incidences_and_hairs) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("lattice_incidences_and_hairs", 20261126));
  std::uniform_int_distribution<int> small(-6, 6);
  const auto lattice = [&] { return Point3{double(small(rng)), double(small(rng)), double(small(rng))}; };
  float_misses = 0;
  int zeros = 0, hairs = 0;
  for (int i = 0; i < 600; ++i) {
    const Point3 x = lattice() + (i % 2 == 0 ? Point3{0x1p20, -0x1p20, 0x1p20} : Point3{});
    const double hair = i % 2 == 0 ? 0x1p-30 : 0x1p-40;
    const auto plane_through_x = [&](bool by_points) {
      for (;;) {
        const Point3 a = lattice(), b = lattice();
        if (by_points) {
          const Point3 p0 = x + a, p1 = x + b, p2 = x - a - b;
          try {
            return Plane3::through(p0, p1, p2);
          } catch (const std::invalid_argument&) {
            continue;  // collinear
          }
        }
        if (a == Point3{}) continue;
        return Plane3::from_coefficients(a.x, a.y, a.z, a.x * x.x + a.y * x.y + a.z * x.z);
      }
    };
    const Plane3 p = plane_through_x(rng() % 2 == 0), q = plane_through_x(rng() % 2 == 0),
                 r = plane_through_x(rng() % 2 == 0);
    if (!independent(p, q, r)) continue;
    Plane3 s = plane_through_x(rng() % 2 == 0);
    BOOST_TEST((oracle_side(s, oracle_point(p, q, r)) == Sign::zero));
    check_three_plane(s, p, q, r);
    check_point(s, x);
    ++zeros;
    if (s.kind == Plane3::Kind::through_points) {
      s.points[0].x += rng() % 2 == 0 ? hair : -hair;
    } else {
      s.coefficients[3] += rng() % 2 == 0 ? hair : -hair;
    }
    if (oracle_side(s, oracle_point(p, q, r)) == Sign::zero) continue;
    check_three_plane(s, p, q, r);
    check_point(s, x);
    ++hairs;
  }
  BOOST_TEST(zeros >= 300);
  BOOST_TEST(hairs >= 150);
  BOOST_TEST_MESSAGE("lattice: " << zeros << " incidences, " << hairs << " hairs; Float misses " << float_misses);
}

BOOST_AUTO_TEST_CASE(opposite_and_validation) {
  const Plane3 s = Plane3::through({0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // z = 0, normal +z
  BOOST_TEST((rk::side_of_plane<rk::Checked>(s, Point3{0.3, 0.2, 1}) == Sign::positive));
  BOOST_TEST((rk::side_of_plane<rk::Checked>(s.opposite(), Point3{0.3, 0.2, 1}) == Sign::negative));
  const Plane3 c = Plane3::from_coefficients(1, 2, 3, 4);
  BOOST_TEST((rk::side_of_plane<rk::Checked>(c, Point3{1, 0, 1}) == Sign::zero));
  BOOST_TEST((rk::side_of_plane<rk::Checked>(c.opposite(), Point3{1, 1, 1}) == Sign::negative));
  BOOST_CHECK_THROW(Plane3::through({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), std::invalid_argument);
  BOOST_CHECK_THROW(Plane3::from_coefficients(0, 0, 0, 1), std::invalid_argument);
  // The three-plane side counts as a plane_side call.
  const auto before = rk::predicate_counters();
  const Plane3 x = Plane3::from_coefficients(1, 0, 0, 0), y = Plane3::from_coefficients(0, 1, 0, 0),
               z = Plane3::from_coefficients(0, 0, 1, 0);
  BOOST_TEST((rk::side_of_plane<rk::Filtered>(c, x, y, z) == Sign::negative));
  [[maybe_unused]] const auto spent = rk::predicate_counters() - before;
#if ROCKCONTACT_PREDICATE_STATS
  BOOST_TEST(spent.calls[static_cast<std::size_t>(rk::PredicateKind::plane_side)] == 1u);
#endif
}

namespace {

// The three-plane side in RunningErrorOf<V> against the same formula in GMP rationals on 1000
// random planes and lattice incidences moved by a hair, under each rounding mode of `modes`;
// the bound must hold every time. Returns the number of cases checked.
template <class V>
int three_plane_side_bound_cases(std::mt19937_64& rng, std::initializer_list<int> modes) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> small(-6, 6);
  const auto point = [&] { return Point3{u(rng), u(rng), u(rng)}; };
  const auto lattice = [&] { return Point3{double(small(rng)), double(small(rng)), double(small(rng))}; };
  int checked = 0;
  for (const int mode : modes) {
    for (int i = 0; i < 1000; ++i) {
      std::array<Plane3, 4> planes;
      for (Plane3& plane : planes) {
        for (;;) {
          try {
            if (i % 2 == 0) {
              plane = Plane3::through(point(), point(), point());
            } else {
              const Point3 a = lattice(), b = lattice();
              plane = Plane3::through(a, b, Point3{} - a - b);  // through the origin
            }
            break;
          } catch (const std::invalid_argument&) {
          }
        }
      }
      if (i % 2 == 1) planes[0].points[0].x += 0x1p-40;
      const auto& [s, p, q, r] = planes;
      if (!independent(p, q, r)) continue;
      std::fesetround(mode);
      const auto v = rk::detail::three_plane_side_formula<rk::detail::RunningErrorOf<V>>(s, p, q, r, p.reference());
      std::fesetround(FE_TONEAREST);
      const mpq_class exact = rk::detail::three_plane_side_formula<mpq_class>(s, p, q, r, p.reference());
      mpq_class value;
      if constexpr (std::is_same_v<V, double>) {
        value = v.value;
      } else {
        value = mpq_class(v.value.hi) + mpq_class(v.value.lo);
      }
      BOOST_TEST(abs(value - exact) <= mpq_class(rk::detail::bound_rounding_margin * v.error));
      ++checked;
    }
  }
  return checked;
}

}  // namespace

// The running error bound of the three-plane side's double filter (detail/running_error.hpp),
// re-derived: the formula in RunningError against the same formula in GMP rationals, on random
// planes and on lattice incidences moved by a hair (where the value is tiny and the bound is
// what decides), under rounding to nearest (the library's mode) and upward (the bound takes a
// whole ulp per operation, enough for any mode barring overflow).
BOOST_AUTO_TEST_CASE(running_error_bound_holds) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("running_error_bound_holds", 20261130));
  BOOST_TEST(three_plane_side_bound_cases<double>(rng, {FE_TONEAREST, FE_UPWARD}) >= 1500);
}

// The same in DoubleDouble, the lazy stage of the Exact volume: round to nearest only, the
// mode every construction runs in (double_double.hpp requires it).
BOOST_AUTO_TEST_CASE(double_double_running_error_bound_holds) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("double_double_running_error_bound_holds", 20261127));
  BOOST_TEST(three_plane_side_bound_cases<rk::detail::DoubleDouble>(rng, {FE_TONEAREST}) >= 750);
}
