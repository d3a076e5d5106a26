#define BOOST_TEST_MODULE kernel3d_contact_set
#include "rockcontact/kernel/3d/contact_set.hpp"

#include <boost/test/unit_test.hpp>

#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "polyhedra.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/contact3d.hpp"
#include "rockcontact/testing/seed.hpp"

// The contact set of touching convex polyhedra against closed forms (a square, a rectangle, an
// octagon cut out by crossings, segments, points, one of each kind of touch), the contact3d
// reference (exact dimension and corners of 55 touching pairs), and CGAL's exact 2D
// intersection of a random tetrahedron's lowest feature with a cube's top face.

namespace rk = rockcontact::kernel;
namespace rt = rockcontact::testing;
using rk::ConvexPolyhedron;
using rk::Point3;

namespace {

// Same dimension, as many corners, and each corner within `tolerance` of one in the other list.
bool same_set(const rk::ContactSet& set, int dimension, const std::vector<Point3>& corners, double tolerance) {
  const auto covered = [&](const std::vector<Point3>& from, const std::vector<Point3>& to) {
    return std::all_of(from.begin(), from.end(), [&](const Point3& p) {
      return std::any_of(to.begin(), to.end(), [&](const Point3& q) { return rt::distance(p, q) <= tolerance; });
    });
  };
  return set.dimension == dimension && set.vertices.size() == corners.size() && covered(set.vertices, corners) &&
         covered(corners, set.vertices);
}

template <class Policy>
void check_closed_form(const ConvexPolyhedron& a, const ConvexPolyhedron& b, int dimension,
                       const std::vector<Point3>& corners) {
  // Input corners are exact; crossings here are dyadic and constructed within a few ulps.
  const double tolerance = 0x1p-50 * (1 + std::fabs(corners[0].x));
  BOOST_TEST_CONTEXT(a.name() << " / " << b.name() << " under " << Policy::name) {
    const auto ab = rk::contact_set<Policy>(a, b);
    const auto ba = rk::contact_set<Policy>(b, a);
    BOOST_TEST_REQUIRE(ab.has_value());
    BOOST_TEST_REQUIRE(ba.has_value());
    BOOST_TEST(same_set(*ab, dimension, corners, tolerance));
    BOOST_TEST(same_set(*ba, dimension, corners, tolerance));
  }
}

void check_staged(const ConvexPolyhedron& a, const ConvexPolyhedron& b, int dimension,
                  const std::vector<Point3>& corners) {
  check_closed_form<rk::Filtered>(a, b, dimension, corners);
  check_closed_form<rk::Exact>(a, b, dimension, corners);
  check_closed_form<rk::Checked>(a, b, dimension, corners);
}

// The square |x - cx| + |y - cy| <= r, counter-clockwise.
std::vector<std::pair<double, double>> diamond(double cx, double cy, double r) {
  return {{cx + r, cy}, {cx, cy + r}, {cx - r, cy}, {cx, cy - r}};
}

}  // namespace

BOOST_AUTO_TEST_CASE(closed_forms) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  check_staged(a, rt::unit_cube_at("face on face", {1, 0, 0}), 2, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}});
  check_staged(a, rt::unit_cube_at("face on face, shifted", {1, 0.5, 0.25}), 2,
               {{1, 0.5, 0.25}, {1, 1, 0.25}, {1, 1, 1}, {1, 0.5, 1}});
  check_staged(a, rt::unit_cube_at("edge on edge", {1, 1, 0.5}), 1, {{1, 1, 0.5}, {1, 1, 1}});
  check_staged(a, rt::unit_cube_at("vertex on vertex", {1, 1, 1}), 0, {{1, 1, 1}});
  check_staged(a, rt::octahedron("vertex on face", {0.5, 0.5, 1.5}, 0.5), 0, {{0.5, 0.5, 1}});
  check_staged(a, rt::octahedron("vertex on edge", {0.5, 1.5, 1}, 0.5), 0, {{0.5, 1, 1}});
  check_staged(a, rt::crossing_tetrahedron("edge across edge", 0), 0, {{0.5, 1, 1}});
  // A diamond prism standing on the top face, |x - 0.5| + |y - 0.5| <= 0.625: the octagon of
  // eight crossings, 0.125 either side of each edge's midpoint.
  check_staged(a, rt::prism("diamond on top", diamond(0.5, 0.5, 0.625), 1, 2), 2,
               {{1, 0.375, 1}, {1, 0.625, 1}, {0.625, 1, 1}, {0.375, 1, 1}, {0, 0.625, 1}, {0, 0.375, 1},
                {0.375, 0, 1}, {0.625, 0, 1}});
  // The same prism lying against the face x = 1 with its edge x = 1, y = 0.5: the edge's
  // part inside the face, ending at an input vertex below and at a crossing with the face's
  // top edge above.
  check_staged(a, rt::prism("diamond edge on face", diamond(1.5, 0.5, 0.5), 0.25, 0.75), 1,
               {{1, 0.5, 0.25}, {1, 0.5, 0.75}});
  check_staged(a, rt::prism("diamond edge across face", diamond(1.5, 0.5, 0.5), 0.5, 1.5), 1,
               {{1, 0.5, 0.5}, {1, 0.5, 1}});
  // The octagon 2^20 m from the origin.
  const Point3 o{0x1p20, -0x1p20, 0x1p20};
  check_staged(rt::unit_cube_at("far", o),
               rt::prism("far diamond", diamond(o.x + 0.5, o.y + 0.5, 0.625), o.z + 1, o.z + 2), 2,
               {{o.x + 1, o.y + 0.375, o.z + 1}, {o.x + 1, o.y + 0.625, o.z + 1}, {o.x + 0.625, o.y + 1, o.z + 1},
                {o.x + 0.375, o.y + 1, o.z + 1}, {o.x, o.y + 0.625, o.z + 1}, {o.x, o.y + 0.375, o.z + 1},
                {o.x + 0.375, o.y, o.z + 1}, {o.x + 0.625, o.y, o.z + 1}});
}

BOOST_AUTO_TEST_CASE(only_touching_pairs) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  BOOST_TEST(!rk::contact_set<rk::Filtered>(a, rt::unit_cube_at("apart", {1 + 0x1p-40, 0, 0})).has_value());
  BOOST_TEST(!rk::contact_set<rk::Exact>(a, rt::unit_cube_at("overlap", {1 - 0x1p-40, 0, 0})).has_value());
}

// The README's tolerance: dimension exact, each corner within 1e-9 scale of one in the other
// list (a corner constructed in double 2^20 m from the origin is rounded by up to 2^-33 m; a
// wrong corner is off by far more), and no extra or missing corner.
// `worst` collects the largest distance / scale from a corner to the nearest reference corner.
template <class Policy>
int check_reference_sets(bool assert, double& worst) {
  int misses = 0;
  for (const auto& pair : rt::contact3d_pairs()) {
    const auto set = rk::contact_set<Policy>(pair.cp, pair.tp);
    const bool touch = pair.expected.at("status") == "touch";
    bool ok = set.has_value() == touch;
    if (ok && touch) {
      const auto& reference = pair.expected.at("contact_set");
      std::vector<Point3> corners;
      for (const auto& v : reference.at("vertices")) corners.push_back(rt::point(v));
      const double scale = rt::number(pair.expected.at("scale"));
      ok = same_set(*set, reference.at("dimension").get<int>(), corners, 1e-9 * scale);
      for (const Point3& p : set->vertices) {
        double nearest = INFINITY;
        for (const Point3& q : corners) nearest = std::min(nearest, rt::distance(p, q));
        worst = std::max(worst, nearest / scale);
      }
    }
    if (assert) {
      BOOST_TEST_INFO("pair " << pair.id << " under " << Policy::name);
      BOOST_TEST(ok);
    }
    misses += !ok;
  }
  return misses;
}

BOOST_AUTO_TEST_CASE(contact3d_reference_sets) {
  BOOST_TEST_REQUIRE(rt::contact3d_pairs().size() == 132u);
  double filtered = 0, exact = 0, checked = 0, unchecked = 0;
  check_reference_sets<rk::Filtered>(true, filtered);
  check_reference_sets<rk::Exact>(true, exact);
  check_reference_sets<rk::Checked>(true, checked);
  BOOST_TEST_MESSAGE("contact3d: largest corner error / scale: Filtered " << filtered << ", Exact " << exact);
  BOOST_TEST_MESSAGE("contact3d: Float's contact set differs from the reference on "
                     << check_reference_sets<rk::Float>(false, unchecked) << " of 132 pairs");
}

namespace {

using CgalKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
using CgalPoint = CgalKernel::Point_2;

// The corners of the tetrahedron's lowest feature (a vertex, an edge or a face, all at z = 1)
// intersected with the unit square, by CGAL in exact arithmetic; the convex hull drops any
// collinear or repeated point of CGAL's answer.
std::vector<Point3> cgal_corners(const std::vector<Point3>& feature) {
  const CgalKernel::Iso_rectangle_2 square(CgalPoint(0, 0), CgalPoint(1, 1));
  std::vector<CgalPoint> f;
  for (const Point3& p : feature) f.emplace_back(p.x, p.y);
  std::vector<CgalPoint> points;
  if (f.size() == 1) {
    if (!square.has_on_unbounded_side(f[0])) points.push_back(f[0]);
  } else if (f.size() == 2) {
    if (const auto r = CGAL::intersection(CgalKernel::Segment_2(f[0], f[1]), square)) {
      if (const auto* p = boost::get<CgalPoint>(&*r)) points.push_back(*p);
      if (const auto* s = boost::get<CgalKernel::Segment_2>(&*r)) {
        points.insert(points.end(), {s->source(), s->target()});
      }
    }
  } else if (const auto r = CGAL::intersection(CgalKernel::Triangle_2(f[0], f[1], f[2]), square)) {
    if (const auto* p = boost::get<CgalPoint>(&*r)) points.push_back(*p);
    if (const auto* s = boost::get<CgalKernel::Segment_2>(&*r)) {
      points.insert(points.end(), {s->source(), s->target()});
    }
    if (const auto* t = boost::get<CgalKernel::Triangle_2>(&*r)) {
      points.insert(points.end(), {t->vertex(0), t->vertex(1), t->vertex(2)});
    }
    if (const auto* v = boost::get<std::vector<CgalPoint>>(&*r)) points.insert(points.end(), v->begin(), v->end());
  }
  std::vector<CgalPoint> hull;
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull));
  std::vector<Point3> out;
  for (const CgalPoint& p : hull) out.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), 1.0});
  return out;
}

}  // namespace

// A tetrahedron with vertices on a 1/8 grid, z in 0..3/8 (many ties, so its lowest feature is
// often an edge or a face, and its edges often pass through the square's corners or along its
// sides), is lowered onto the unit cube's top face: its lowest z moved to 1, exactly on the
// grid. It then lies above the plane z = 1 and meets the cube in its lowest feature's
// intersection with the top square, which CGAL computes; empty means separate. Both blocks are
// mapped by a random symmetry of the axes (exact), so the contact plane takes every axis and
// orientation.
BOOST_AUTO_TEST_CASE(random_against_cgal_intersection) {
  std::mt19937_64 rng(rt::seed_for("random_against_cgal_intersection", 19));
  std::uniform_int_distribution<int> xy(-4, 12), z(0, 3), flip(0, 1);
  int compared = 0, by_dimension[3] = {0, 0, 0};
  const ConvexPolyhedron cube = rt::unit_cube_at("cube", {0, 0, 0});
  for (int trial = 0; trial < 600; ++trial) {
    std::vector<Point3> v;
    for (int i = 0; i < 4; ++i) v.push_back({xy(rng) / 8.0, xy(rng) / 8.0, z(rng) / 8.0});
    const double lowest = std::min({v[0].z, v[1].z, v[2].z, v[3].z});
    for (Point3& p : v) p.z += 1 - lowest;
    const auto tet = rt::tetrahedron("tet", v);
    if (!tet) continue;
    std::vector<Point3> feature;
    for (const Point3& p : v) {
      if (p.z == 1) feature.push_back(p);
    }
    const std::vector<Point3> corners = cgal_corners(feature);
    rt::AxisMap m;
    std::shuffle(m.axis.begin(), m.axis.end(), rng);
    for (double& s : m.sign) s = flip(rng) ? -1 : 1;
    std::vector<Point3> mapped_corners;
    for (const Point3& p : corners) mapped_corners.push_back(m(p));
    const ConvexPolyhedron a = rt::mapped(cube, m), b = rt::mapped(*tet, m);
    const int dimension = std::min<int>(2, static_cast<int>(corners.size()) - 1);
    BOOST_TEST_CONTEXT("trial " << trial) {
      for (const auto& set : {rk::contact_set<rk::Filtered>(a, b), rk::contact_set<rk::Exact>(a, b),
                              rk::contact_set<rk::Checked>(b, a)}) {
        BOOST_TEST(set.has_value() == !corners.empty());
        // The crossings are dyadic-rational combinations of grid points; 2^-48 covers a
        // construction in double at this size.
        if (set && !corners.empty()) BOOST_TEST(same_set(*set, dimension, mapped_corners, 0x1p-48));
      }
    }
    if (!corners.empty()) ++by_dimension[dimension];
    ++compared;
  }
  BOOST_TEST_MESSAGE("random touching tetrahedra: " << compared << " compared, contact sets of dimension 0/1/2: "
                                                     << by_dimension[0] << "/" << by_dimension[1] << "/"
                                                     << by_dimension[2]);
  BOOST_TEST(std::min({by_dimension[0], by_dimension[1], by_dimension[2]}) >= 20);
}
