#define BOOST_TEST_MODULE kernel3d_distance
#include "rockcontact/kernel/3d/distance.hpp"

#include <boost/test/unit_test.hpp>

#include <CGAL/Exact_rational.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "polyhedra.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/contact3d.hpp"
#include "rockcontact/testing/seed.hpp"

// The distance and closest points of separate convex polyhedra against closed forms (cubes and
// an octahedron at exactly known offsets), the contact3d reference distances (exact, 132 pairs),
// and CGAL's Polytope_distance_d (an exact quadratic program, independent of the feature
// enumeration) on random pairs.

namespace rk = rockcontact::kernel;
namespace rt = rockcontact::testing;
using rk::ConvexPolyhedron;
using rk::Point3;

namespace {

template <class Policy>
void check_closed_form(const ConvexPolyhedron& a, const ConvexPolyhedron& b, double distance, Point3 on_a,
                       Point3 on_b) {
  BOOST_TEST_CONTEXT(a.name() << " / " << b.name() << " under " << Policy::name) {
    const auto s = rk::separation<Policy>(a, b);
    BOOST_TEST_REQUIRE(s.has_value());
    // Every closed form here is a dyadic configuration: the exact result is a double or
    // within 2^-52 of one; 4 ulps covers the rounding of a local-frame construction.
    BOOST_TEST(s->distance == distance, boost::test_tools::tolerance(0x1p-50));
    BOOST_TEST(rt::distance(s->point_a, on_a) <= 0x1p-50 * (1 + std::fabs(on_a.x)));
    BOOST_TEST(rt::distance(s->point_b, on_b) <= 0x1p-50 * (1 + std::fabs(on_b.x)));
  }
}

template <class Policy>
void check_unique_closed_form(const ConvexPolyhedron& a, const ConvexPolyhedron& b, double distance, Point3 on_a,
                              Point3 on_b) {
  check_closed_form<Policy>(a, b, distance, on_a, on_b);
  check_closed_form<Policy>(b, a, distance, on_b, on_a);
}

void check_staged(const ConvexPolyhedron& a, const ConvexPolyhedron& b, double distance, Point3 on_a, Point3 on_b) {
  check_unique_closed_form<rk::Filtered>(a, b, distance, on_a, on_b);
  check_unique_closed_form<rk::Exact>(a, b, distance, on_a, on_b);
  check_unique_closed_form<rk::Checked>(a, b, distance, on_a, on_b);
}

// Largest signed distance of x above a face plane of p (<= 0 inside, 0 on the boundary),
// evaluated in double from differences to a face vertex.
double height_above(const ConvexPolyhedron& p, const Point3& x) {
  double worst = -INFINITY;
  for (const auto& face : p.faces()) {
    const Point3 &f0 = p[face[0]], &f1 = p[face[1]], &f2 = p[face[2]];
    const double ux = f1.x - f0.x, uy = f1.y - f0.y, uz = f1.z - f0.z;
    const double vx = f2.x - f0.x, vy = f2.y - f0.y, vz = f2.z - f0.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double h = (nx * (x.x - f0.x) + ny * (x.y - f0.y) + nz * (x.z - f0.z)) / std::hypot(nx, ny, nz);
    worst = std::max(worst, h);
  }
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_CASE(closed_forms) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  // Face to face, 0.5 apart along x, over the whole unit square: the closest points are any
  // pair at the same (y, z) on x = 1 and x = 1.5; also 2^20 m from the origin.
  for (const Point3 o : {Point3{0, 0, 0}, Point3{0x1p20, -0x1p20, 0x1p20}}) {
    const auto s = rk::separation<rk::Exact>(rt::unit_cube_at("a", o), rt::unit_cube_at("b", {o.x + 1.5, o.y, o.z}));
    BOOST_TEST_REQUIRE(s.has_value());
    BOOST_TEST(s->distance == 0.5);
    BOOST_TEST(s->point_a.x == o.x + 1);
    BOOST_TEST(s->point_b.x == o.x + 1.5);
    BOOST_TEST(rt::distance(s->point_a, s->point_b) == 0.5);
  }
  // Vertex to vertex along the diagonal: sqrt 3, between (1, 1, 1) and (2, 2, 2) only.
  check_staged(a, rt::unit_cube_at("diagonal", {2, 2, 2}), std::sqrt(3.0), {1, 1, 1}, {2, 2, 2});
  // Edge to edge, perpendicular: the octahedron centred at (0.5, 1.5, 1.5) with radius 0.5 has
  // its edge from (0.5, 1.5, 1) to (0.5, 1, 1.5) on y + z = 2.5, the cube's edge x in [0, 1],
  // y = z = 1 on y + z = 2; the common perpendicular from (0.5, 1, 1) to (0.5, 1.25, 1.25) has
  // length sqrt(2) / 4.
  check_staged(a, rt::octahedron("edge to edge", {0.5, 1.5, 1.5}, 0.5), std::sqrt(2.0) / 4, {0.5, 1, 1},
               {0.5, 1.25, 1.25});
  // Vertex to face: the octahedron's lowest vertex 2^-40 above the centre of the top face.
  check_staged(a, rt::octahedron("vertex above face", {0.5, 0.5, 1.5 + 0x1p-40}, 0.5), 0x1p-40, {0.5, 0.5, 1},
               {0.5, 0.5, 1 + 0x1p-40});
  // Vertex to edge: the octahedron's vertex (0.5, 1.25, 1.25) above the edge y = z = 1.
  check_staged(a, rt::octahedron("vertex to edge", {0.5, 1.25 + 0.375, 1.25}, 0.375), std::sqrt(2.0) / 4,
               {0.5, 1, 1}, {0.5, 1.25, 1.25});
}

BOOST_AUTO_TEST_CASE(only_separate_pairs) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  BOOST_TEST(!rk::separation<rk::Filtered>(a, rt::unit_cube_at("face on face", {1, 0.5, 0})).has_value());
  BOOST_TEST(!rk::separation<rk::Exact>(a, rt::unit_cube_at("vertex on vertex", {1, 1, 1})).has_value());
  BOOST_TEST(!rk::separation<rk::Filtered>(a, rt::unit_cube_at("overlap", {0.5, 0.5, 0.5})).has_value());
}

// The reference distance of each separate pair (exact rational squared distance, root at 50
// digits), with the README's tolerance; the closest points must lie on their blocks and be the
// reported distance apart, within 1e-9 scale: they are rounded to doubles at up to 2^20 m
// from the origin (2^-33 m per coordinate) and the test's own plane evaluation rounds too, so
// a tighter absolute bound would not hold on the offset pairs, while a wrong feature is off by
// far more on every pair.
// `worst` collects the largest |distance - reference| / scale.
template <class Policy>
int check_reference_distances(bool assert, double& worst) {
  int misses = 0;
  for (const auto& pair : rt::contact3d_pairs()) {
    const auto s = rk::separation<Policy>(pair.cp, pair.tp);
    const bool separate = pair.expected.at("status") == "separate";
    const double scale = rt::number(pair.expected.at("scale"));
    bool ok = s.has_value() == separate;
    if (ok && separate) {
      const double reference = rt::number(pair.expected.at("distance"));
      const double slack = 1e-9 * scale;
      worst = std::max(worst, std::fabs(s->distance - reference) / scale);
      if constexpr (Policy::kind == rk::PolicyKind::exact) {
        // Exact rounds the exact root once, as stod rounds the 50-digit reference: within an ulp.
        BOOST_TEST_INFO("pair " << pair.id);
        BOOST_TEST(s->distance == reference, boost::test_tools::tolerance(0x1p-52));
      }
      ok = rt::metric_matches(s->distance, reference, scale) &&
           std::fabs(rt::distance(s->point_a, s->point_b) - s->distance) <= slack &&
           std::fabs(height_above(pair.cp, s->point_a)) <= slack &&
           std::fabs(height_above(pair.tp, s->point_b)) <= slack;
    }
    if (assert) {
      BOOST_TEST_INFO("pair " << pair.id << " under " << Policy::name);
      BOOST_TEST(ok);
    }
    misses += !ok;
  }
  return misses;
}

BOOST_AUTO_TEST_CASE(contact3d_reference_distances) {
  BOOST_TEST_REQUIRE(rt::contact3d_pairs().size() == 132u);
  double filtered = 0, exact = 0, checked = 0, unchecked = 0;
  check_reference_distances<rk::Filtered>(true, filtered);
  check_reference_distances<rk::Exact>(true, exact);
  check_reference_distances<rk::Checked>(true, checked);
  BOOST_TEST_MESSAGE("contact3d: largest |distance - reference| / scale: Filtered " << filtered << ", Exact " << exact);
  BOOST_TEST_MESSAGE("contact3d: Float's separation differs from the reference on "
                     << check_reference_distances<rk::Float>(false, unchecked) << " of 132 pairs");
}

namespace {

using CgalKernel = CGAL::Simple_cartesian<double>;
using CgalTraits = CGAL::Polytope_distance_d_traits_3<CgalKernel, CGAL::Exact_rational, double>;

// CGAL's exact squared distance of the two vertex sets' convex hulls, rounded to double once.
double cgal_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  std::vector<CgalKernel::Point_3> p, q;
  for (const Point3& v : a.vertices()) p.emplace_back(v.x, v.y, v.z);
  for (const Point3& v : b.vertices()) q.emplace_back(v.x, v.y, v.z);
  const CGAL::Polytope_distance_d<CgalTraits> pd(p.begin(), p.end(), q.begin(), q.end());
  const CGAL::Exact_rational d2 = pd.squared_distance_numerator() / pd.squared_distance_denominator();
  return std::sqrt(CGAL::to_double(d2));
}

// A tetrahedron of random points in the unit cube around `at`; nullopt when they are coplanar.
std::optional<ConvexPolyhedron> random_tetrahedron(std::mt19937_64& rng, Point3 at, const std::string& name) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point3> v;
  for (int i = 0; i < 4; ++i) v.push_back({at.x + u(rng), at.y + u(rng), at.z + u(rng)});
  return rt::tetrahedron(name, std::move(v));
}

}  // namespace

// Random tetrahedra, the second moved by a random offset of length 0.75 to 1.5 and far from the
// origin in half the trials; kept when separate. Exact must agree with CGAL's exact squared
// distance to a few ulps (its root and CGAL's rounded square root each round twice: below
// 2^-51 relative together); Filtered within the README's tolerance; the contact3d separate
// pairs are compared too.
BOOST_AUTO_TEST_CASE(against_cgal_polytope_distance) {
  std::mt19937_64 rng(rt::seed_for("against_cgal_polytope_distance", 19));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; compared < 40 && trial < 400; ++trial) {
    const Point3 base = trial % 2 == 0 ? Point3{0, 0, 0} : Point3{0x1p20, -0x1p20, 0x1p19};
    Point3 d{u(rng), u(rng), u(rng)};
    const double length = std::hypot(d.x, d.y, d.z);
    if (length < 0.1) continue;
    const double r = 0.75 + 0.75 * (u(rng) + 1) / 2;
    d = {base.x + d.x * r / length, base.y + d.y * r / length, base.z + d.z * r / length};
    const auto a = random_tetrahedron(rng, base, "a");
    const auto b = random_tetrahedron(rng, d, "b");
    if (!a || !b || rk::classify_overlap<rk::Exact>(*a, *b) != rk::Overlap::separate) continue;
    const double reference = cgal_distance(*a, *b);
    BOOST_TEST_CONTEXT("trial " << trial) {
      const auto exact = rk::separation<rk::Exact>(*a, *b);
      const auto filtered = rk::separation<rk::Filtered>(*a, *b);
      BOOST_TEST(exact->distance == reference, boost::test_tools::tolerance(0x1p-51));
      BOOST_TEST(rt::metric_matches(filtered->distance, reference, 2.0));
      // The exact distance does not depend on the order of the pair.
      BOOST_TEST(rk::separation<rk::Exact>(*b, *a)->distance == exact->distance);
      // The closest points lie on their blocks and are the distance apart, up to their
      // rounding (2^-33 m per coordinate 2^20 m from the origin; the pairs' extent is about 2).
      for (const auto& s : {*exact, *filtered}) {
        BOOST_TEST(std::fabs(height_above(*a, s.point_a)) <= 1e-9);
        BOOST_TEST(std::fabs(height_above(*b, s.point_b)) <= 1e-9);
        BOOST_TEST(std::fabs(rt::distance(s.point_a, s.point_b) - s.distance) <= 1e-9);
      }
    }
    ++compared;
  }
  BOOST_TEST(compared == 40);
  for (const auto& pair : rt::contact3d_pairs()) {
    if (pair.expected.at("status") != "separate") continue;
    BOOST_TEST_INFO("pair " << pair.id);
    BOOST_TEST(rk::separation<rk::Exact>(pair.cp, pair.tp)->distance == cgal_distance(pair.cp, pair.tp),
               boost::test_tools::tolerance(0x1p-51));
  }
}
