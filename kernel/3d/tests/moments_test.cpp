#define BOOST_TEST_MODULE kernel3d_moments
#include "rockcontact/kernel/3d/moments.hpp"

#include <gmpxx.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

// Volume moments against closed forms computed in exact rationals (GMP): boxes (products of
// one-dimensional integrals), tetrahedra (the unit simplex's moments carried by an affine
// map), a box turned by a rotation with rational entries (Pythagorean triples 3-4-5 and
// 5-12-13, so every rotated vertex is an exact double and the reference is R M Rᵀ), and that
// box 10^6 m from the origin.
//
// Tolerance (moments.hpp): every term of the local sums is bounded by V diam^k (the
// tetrahedra from a vertex of a convex block are all positively oriented, so Σ|D| = 6V), the
// shift adds o-terms bounded by V |o|^k, and each result takes fewer than 30 roundings on
// these terms, so |error| <= 64 u V R^k with R = the largest |coordinate| of a vertex plus the
// diameter, k = 0, 1, 2 for the volume, first and second moments. At the 10^6 m offset this
// is what the local frame buys: the same sums in global coordinates would cancel terms of size
// R³ ~ 10^18 m³ to get V ~ 6 m³, an error near u R³ ~ 10^2 m³, far outside 64 u V.

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rk::Point3;

namespace {

constexpr double u = 0x1p-53;

struct ExactMoments {
  mpq_class volume;
  std::array<mpq_class, 3> first;
  std::array<std::array<mpq_class, 3>, 3> second;  // ∫ x_i x_j dV
};

mpq_class q(double x) { return mpq_class(x); }

// ∫_lo^hi t^k dt for k = 0, 1, 2.
std::array<mpq_class, 3> interval(double lo, double hi) {
  const mpq_class l = q(lo), h = q(hi);
  return {h - l, (h * h - l * l) / 2, (h * h * h - l * l * l) / 3};
}

// The box [lo, hi] as a product of intervals: ∫ x^α y^β z^γ = I_x[α] I_y[β] I_z[γ].
ExactMoments box_moments(Point3 lo, Point3 hi) {
  const std::array<std::array<mpq_class, 3>, 3> i{interval(lo.x, hi.x), interval(lo.y, hi.y), interval(lo.z, hi.z)};
  ExactMoments m;
  m.volume = i[0][0] * i[1][0] * i[2][0];
  for (int a = 0; a < 3; ++a) {
    m.first[a] = m.volume / i[a][0] * i[a][1];
    for (int b = 0; b < 3; ++b) {
      std::array<int, 3> power{0, 0, 0};
      ++power[a];
      ++power[b];
      m.second[a][b] = i[0][power[0]] * i[1][power[1]] * i[2][power[2]];
    }
  }
  return m;
}

std::vector<Point3> box_vertices(Point3 lo, Point3 hi) {
  return {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
}
const std::vector<ConvexPolyhedron::Face> box_faces{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

double reach(const ConvexPolyhedron& p) {
  double r = 0.0, lo = INFINITY, hi = -INFINITY;
  for (const Point3& v : p.vertices()) {
    r = std::max({r, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    lo = std::min({lo, v.x, v.y, v.z});
    hi = std::max({hi, v.x, v.y, v.z});
  }
  return r + std::sqrt(3.0) * (hi - lo);
}

void check(const ConvexPolyhedron& p, const ExactMoments& e) {
  const rk::Moments3 m = rk::moments(p);
  const double v = e.volume.get_d();
  const double r = reach(p);
  BOOST_TEST_INFO(p.name());
  BOOST_TEST(std::fabs(m.volume - v) <= 64 * u * v);
  const std::array<double, 3> first{m.first.x, m.first.y, m.first.z};
  for (int i = 0; i < 3; ++i) {
    BOOST_TEST_INFO(p.name() << " first[" << i << "]");
    BOOST_TEST(std::fabs(first[i] - e.first[i].get_d()) <= 64 * u * v * r);
  }
  const std::array<std::array<double, 3>, 3> second{
      {{m.xx, m.xy, m.zx}, {m.xy, m.yy, m.yz}, {m.zx, m.yz, m.zz}}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      BOOST_TEST_INFO(p.name() << " second[" << i << "][" << j << "] = " << second[i][j] << " vs "
                               << e.second[i][j].get_d());
      BOOST_TEST(std::fabs(second[i][j] - e.second[i][j].get_d()) <= 64 * u * v * r * r);
    }
  }
}

// The rotation Rz(3/5, 4/5) Rx(5/13, 12/13): entries k / 65 (rows listed), exactly orthogonal.
const std::array<std::array<mpq_class, 3>, 3> rotation = [] {
  const mpq_class c1(3, 5), s1(4, 5), c2(5, 13), s2(12, 13);
  // Rz = [[c1, -s1, 0], [s1, c1, 0], [0, 0, 1]], Rx = [[1, 0, 0], [0, c2, -s2], [0, s2, c2]].
  return std::array<std::array<mpq_class, 3>, 3>{{{c1, -s1 * c2, s1 * s2}, {s1, c1 * c2, -c1 * s2}, {0, s2, c2}}};
}();

// x -> R x + t of the exact moments: V unchanged, first' = R f + t V,
// second' = R M Rᵀ + (R f) tᵀ + t (R f)ᵀ + t tᵀ V.
ExactMoments transform(const ExactMoments& m, Point3 t) {
  const std::array<mpq_class, 3> tt{q(t.x), q(t.y), q(t.z)};
  ExactMoments r;
  r.volume = m.volume;
  std::array<mpq_class, 3> rf;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) rf[i] += rotation[i][k] * m.first[k];
    r.first[i] = rf[i] + tt[i] * m.volume;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      mpq_class s;
      for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) s += rotation[i][k] * m.second[k][l] * rotation[j][l];
      }
      r.second[i][j] = s + rf[i] * tt[j] + tt[i] * rf[j] + tt[i] * tt[j] * m.volume;
    }
  }
  return r;
}

Point3 apply(const Point3& p, Point3 t) {
  const std::array<mpq_class, 3> x{q(p.x), q(p.y), q(p.z)};
  std::array<double, 3> y{};
  for (int i = 0; i < 3; ++i) {
    const mpq_class yi = rotation[i][0] * x[0] + rotation[i][1] * x[1] + rotation[i][2] * x[2];
    y[i] = yi.get_d();
    BOOST_REQUIRE(mpq_class(y[i]) == yi);  // the construction promises exact doubles
  }
  return {y[0] + t.x, y[1] + t.y, y[2] + t.z};
}

ConvexPolyhedron rotated_box(const std::string& name, Point3 hi, Point3 t) {
  std::vector<Point3> v = box_vertices({0, 0, 0}, hi);
  for (Point3& p : v) p = apply(p, t);
  return ConvexPolyhedron::make(name, std::move(v), box_faces);
}

// The tetrahedron p0 + A u over the unit simplex u >= 0, Σu <= 1, A = [p1 - p0, p2 - p0,
// p3 - p0]: with the unit simplex's ∫ 1 = 1/6, ∫ u_i = 1/24, ∫ u_i² = 1/60, ∫ u_i u_j = 1/120
// (i != j) and J = |det A|: ∫ x = J (p0/6 + A (1/24) 1), ∫ x xᵀ = J (p0 p0ᵀ/6 + p0 (A c)ᵀ +
// (A c) p0ᵀ + A M0 Aᵀ), c = (1/24) 1, M0 the unit matrix of second moments.
ExactMoments tetrahedron_moments(const std::array<Point3, 4>& p) {
  std::array<std::array<mpq_class, 3>, 3> a;  // columns p_k - p0
  const std::array<mpq_class, 3> p0{q(p[0].x), q(p[0].y), q(p[0].z)};
  for (int k = 0; k < 3; ++k) {
    const std::array<mpq_class, 3> pk{q(p[k + 1].x), q(p[k + 1].y), q(p[k + 1].z)};
    for (int i = 0; i < 3; ++i) a[i][k] = pk[i] - p0[i];
  }
  mpq_class det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                  a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  const mpq_class j = abs(det);
  std::array<mpq_class, 3> ac;
  for (int i = 0; i < 3; ++i) ac[i] = (a[i][0] + a[i][1] + a[i][2]) / 24;
  ExactMoments m;
  m.volume = j / 6;
  for (int i = 0; i < 3; ++i) m.first[i] = j * (p0[i] / 6 + ac[i]);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      mpq_class ama;
      for (int r = 0; r < 3; ++r) {
        for (int s = 0; s < 3; ++s) ama += a[i][r] * (r == s ? mpq_class(1, 60) : mpq_class(1, 120)) * a[k][s];
      }
      m.second[i][k] = j * (p0[i] * p0[k] / 6 + p0[i] * ac[k] + ac[i] * p0[k] + ama);
    }
  }
  return m;
}

ConvexPolyhedron tetrahedron(const std::string& name, const std::array<Point3, 4>& p) {
  // Faces CCW from outside for a positively oriented (p1 - p0, p2 - p0, p3 - p0).
  return ConvexPolyhedron::make(name, {p[0], p[1], p[2], p[3]}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

}  // namespace

BOOST_AUTO_TEST_CASE(box_at_the_origin_and_shifted) {
  const Point3 lo{0, 0, 0}, hi{0.5, 1.25, 3};
  check(ConvexPolyhedron::make("box", box_vertices(lo, hi), box_faces), box_moments(lo, hi));
  // The closed forms for a = 0.5, b = 1.25, c = 3 (V = abc, ∫x² = a³bc/3, ∫xy = a²b²c/4),
  // written out once to pin the product formula above.
  const ExactMoments e = box_moments(lo, hi);
  BOOST_TEST(e.volume == mpq_class(15, 8));
  BOOST_TEST(e.second[0][0] == mpq_class(5, 32));       // 0.125 * 1.25 * 3 / 3
  BOOST_TEST(e.second[0][1] == mpq_class(75, 256));     // 0.25 * 1.5625 * 3 / 4
  const Point3 slo{-2.25, 3.5, -0.75}, shi{-1.75, 4.75, 2.25};
  check(ConvexPolyhedron::make("shifted box", box_vertices(slo, shi), box_faces), box_moments(slo, shi));
  const rk::Moments3 m = rk::moments(ConvexPolyhedron::make("shifted box", box_vertices(slo, shi), box_faces));
  const Point3 c = m.centroid();
  BOOST_TEST(std::fabs(c.x - -2.0) <= 64 * u * 8);
  BOOST_TEST(std::fabs(c.y - 4.125) <= 64 * u * 8);
  BOOST_TEST(std::fabs(c.z - 0.75) <= 64 * u * 8);
}

BOOST_AUTO_TEST_CASE(unit_and_general_tetrahedra) {
  const std::array<Point3, 4> unit{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const rk::Moments3 m = rk::moments(tetrahedron("unit tetrahedron", unit));
  // The unit simplex: V = 1/6, ∫x = 1/24, ∫x² = 1/60, ∫xy = 1/120; the float formulas are
  // exact up to a few roundings.
  BOOST_TEST(std::fabs(m.volume - 1.0 / 6) <= 8 * u);
  BOOST_TEST(std::fabs(m.first.y - 1.0 / 24) <= 8 * u);
  BOOST_TEST(std::fabs(m.xx - 1.0 / 60) <= 8 * u);
  BOOST_TEST(std::fabs(m.zz - 1.0 / 60) <= 8 * u);
  BOOST_TEST(std::fabs(m.xy - 1.0 / 120) <= 8 * u);
  BOOST_TEST(std::fabs(m.zx - 1.0 / 120) <= 8 * u);
  check(tetrahedron("unit tetrahedron", unit), tetrahedron_moments(unit));
  // V = |det| / 6 for a skew tetrahedron away from the origin. The edge vectors p_k - p0 are
  // (1.5, 0.25, 0.5), (0.25, 2, -0.5), (-0.5, 0.75, 1.25); expanding along the first row of
  // A = [[1.5, 0.25, -0.5], [0.25, 2, 0.75], [0.5, -0.5, 1.25]]:
  // det = 1.5 (2.5 + 0.375) - 0.25 (0.3125 - 0.375) - 0.5 (-0.125 - 1) = 4.890625 = 313/64.
  const std::array<Point3, 4> skew{{{3.5, -1.25, 2}, {5, -1, 2.5}, {3.75, 0.75, 1.5}, {3, -0.5, 3.25}}};
  const ExactMoments e = tetrahedron_moments(skew);
  BOOST_TEST(e.volume == mpq_class(313, 384));
  check(tetrahedron("skew tetrahedron", skew), e);
}

BOOST_AUTO_TEST_CASE(box_rotated_by_a_rational_rotation) {
  // Edges multiples of 65/64 m, so R x (entries k/65) lands on the grid 1/64 m exactly.
  const Point3 hi{65.0 / 64, 130.0 / 64, 195.0 / 64};
  const Point3 t{0.5, -1.25, 2};
  check(rotated_box("rotated box", hi, t), transform(box_moments({0, 0, 0}, hi), t));
}

BOOST_AUTO_TEST_CASE(rotated_box_far_from_the_origin) {
  // The same box 10^6 m out (exact: coordinates on the grid 1/64 below 2^21). The reference
  // shift is exact; the tolerance (top of file) is relative to R ~ 10^6 m.
  const Point3 hi{65.0 / 64, 130.0 / 64, 195.0 / 64};
  const Point3 t{1e6 + 0.5, -1e6 - 1.25, 1e6 + 2};
  const ConvexPolyhedron far = rotated_box("rotated box at 1e6 m", hi, t);
  check(far, transform(box_moments({0, 0, 0}, hi), t));
  // The volume keeps its relative accuracy (the point of the local frame), and the centroid
  // is within a few ulps of 10^6.
  const rk::Moments3 m = rk::moments(far);
  const double v = (65.0 / 64) * (130.0 / 64) * (195.0 / 64);
  BOOST_TEST(std::fabs(m.volume - v) <= 64 * u * v);
  const ExactMoments e = transform(box_moments({0, 0, 0}, hi), t);
  BOOST_TEST(std::fabs(m.centroid().x - mpq_class(e.first[0] / e.volume).get_d()) <= 64 * u * 2e6);
}

// moments_about: the integrals of x - o, for the rotated box 10^6 m out about one of its own
// vertices, against the exact moments of the box translated by -o (the reference shift is
// exact in rationals). The tolerance is the top of file's with R the box's own size (a few m),
// not 10^6 m: no shift back to the global frame takes place.
BOOST_AUTO_TEST_CASE(moments_about_a_point_near_the_block) {
  const Point3 hi{65.0 / 64, 130.0 / 64, 195.0 / 64};
  const Point3 t{1e6 + 0.5, -1e6 - 1.25, 1e6 + 2};
  const ConvexPolyhedron far = rotated_box("rotated box at 1e6 m", hi, t);
  const Point3 o = far[3];
  const rk::Moments3 m = rk::moments_about(far, o);
  const ExactMoments e = transform(box_moments({0, 0, 0}, hi), {t.x - o.x, t.y - o.y, t.z - o.z});
  const double r = 8.0;  // a vertex's distance from o plus the diameter, m, bounded
  const double v = e.volume.get_d();
  BOOST_TEST(std::fabs(m.volume - v) <= 64 * u * v);
  const std::array<double, 3> first{m.first.x, m.first.y, m.first.z};
  for (int i = 0; i < 3; ++i) BOOST_TEST(std::fabs(first[i] - e.first[i].get_d()) <= 64 * u * v * r);
  BOOST_TEST(std::fabs(m.xx - e.second[0][0].get_d()) <= 64 * u * v * r * r);
  BOOST_TEST(std::fabs(m.xy - e.second[0][1].get_d()) <= 64 * u * v * r * r);
  BOOST_TEST(std::fabs(m.zz - e.second[2][2].get_d()) <= 64 * u * v * r * r);
}
