#define BOOST_TEST_MODULE kernel3d_penetration
#include "rockcontact/kernel/3d/penetration.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "polyhedra.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/contact3d.hpp"

// The minimum translation distance of overlapping convex polyhedra against closed forms (one
// per kind of candidate direction: a face of cp, a face of tp, an edge pair), the contact3d
// reference (exact depth and the exactly tied or 1e-9-near directions) and the defining
// property: moving tp by slightly more than depth * normal separates the pair, by slightly less
// keeps it overlapping, judged by the exact overlap verdict.

namespace rk = rockcontact::kernel;
namespace rt = rockcontact::testing;
using rk::ConvexPolyhedron;
using rk::Point3;

namespace {

template <class Policy>
void check_closed_form(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp, double depth, Point3 normal) {
  BOOST_TEST_CONTEXT(cp.name() << " / " << tp.name() << " under " << Policy::name) {
    const auto p = rk::penetration<Policy>(cp, tp);
    BOOST_TEST_REQUIRE(p.has_value());
    // The closed forms below are unique minima whose depth and normal components are a double
    // or a correctly rounded root; 4 ulps covers a local-frame construction in double.
    BOOST_TEST(p->depth == depth, boost::test_tools::tolerance(0x1p-50));
    BOOST_TEST(rt::distance(p->normal, normal) <= 0x1p-50);
    // With the roles exchanged, the same depth and the opposite direction.
    const auto q = rk::penetration<Policy>(tp, cp);
    BOOST_TEST_REQUIRE(q.has_value());
    BOOST_TEST(q->depth == depth, boost::test_tools::tolerance(0x1p-50));
    BOOST_TEST(rt::distance(q->normal, {-normal.x, -normal.y, -normal.z}) <= 0x1p-50);
  }
}

void check_staged(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp, double depth, Point3 normal) {
  check_closed_form<rk::Filtered>(cp, tp, depth, normal);
  check_closed_form<rk::Exact>(cp, tp, depth, normal);
  check_closed_form<rk::Checked>(cp, tp, depth, normal);
}

}  // namespace

BOOST_AUTO_TEST_CASE(closed_forms) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  // tp = the cube moved by (0.875, 0.25, 0.125) overlaps by 0.125 along x, 0.75 along y and
  // 0.875 along z: out through cp's face x = 1 by 0.125 (every edge pair of two boxes gives an
  // axis again).
  check_staged(a, rt::unit_cube_at("moved", {0.875, 0.25, 0.125}), 0.125, {1, 0, 0});
  // Far from the origin, the same.
  const Point3 o{0x1p20, -0x1p20, 0x1p20};
  check_staged(rt::unit_cube_at("far", o), rt::unit_cube_at("far, moved", {o.x + 0.875, o.y + 0.25, o.z + 0.125}),
               0.125, {1, 0, 0});
  // The octahedron's lowest vertex 0.25 deep below the centre of the top face: up by 0.25; any
  // slanted face or edge direction needs more (e.g. its face normal (1, 1, 1)/sqrt 3 needs
  // 1.25/sqrt 3).
  check_staged(a, rt::octahedron("vertex in face", {0.5, 0.5, 1.25}, 0.5), 0.25, {0, 0, 1});
  // An edge of the tetrahedron pushed by 1/8 along (0, -1, -1) across the cube's top back
  // edge: out along the edges' common normal by sqrt(2)/8 (its faces' and the cube's face
  // directions need at least 0.53).
  check_staged(a, rt::crossing_tetrahedron("edge across edge", 0.125), std::sqrt(2.0) / 8,
               {0, std::sqrt(0.5), std::sqrt(0.5)});
}

BOOST_AUTO_TEST_CASE(only_overlapping_pairs) {
  const ConvexPolyhedron a = rt::unit_cube_at("a", {0, 0, 0});
  BOOST_TEST(!rk::penetration<rk::Filtered>(a, rt::unit_cube_at("face on face", {1, 0.5, 0})).has_value());
  BOOST_TEST(!rk::penetration<rk::Exact>(a, rt::crossing_tetrahedron("edge on edge", 0)).has_value());
  BOOST_TEST(!rk::penetration<rk::Filtered>(a, rt::unit_cube_at("apart", {1.5, 0, 0})).has_value());
}

namespace {

// Is the normal within 1e-6 rad of one of the reference's near-minimal directions? For unit
// vectors the chord |n - r| is within 1e-18 of the angle at this size.
bool normal_matches(const Point3& n, const nlohmann::json& penetration) {
  return std::any_of(penetration.at("normals_near").begin(), penetration.at("normals_near").end(),
                     [&](const nlohmann::json& r) { return rt::distance(n, rt::point(r)) <= 1e-6; });
}

// `worst` collects the largest |depth - reference| / scale.
template <class Policy>
int check_reference_penetrations(bool assert, double& worst) {
  int misses = 0;
  for (const auto& pair : rt::contact3d_pairs()) {
    const auto p = rk::penetration<Policy>(pair.cp, pair.tp);
    const bool overlap = pair.expected.at("status") == "overlap";
    bool ok = p.has_value() == overlap;
    if (ok && overlap) {
      const auto& reference = pair.expected.at("penetration");
      const double scale = rt::number(pair.expected.at("scale"));
      worst = std::max(worst, std::fabs(p->depth - rt::number(reference.at("depth"))) / scale);
      if constexpr (Policy::kind == rk::PolicyKind::exact) {
        // Exact rounds the exact root once, as stod rounds the 50-digit reference: within an ulp.
        BOOST_TEST_INFO("pair " << pair.id);
        BOOST_TEST(p->depth == rt::number(reference.at("depth")), boost::test_tools::tolerance(0x1p-52));
      }
      ok = rt::metric_matches(p->depth, rt::number(reference.at("depth")), scale) &&
           normal_matches(p->normal, reference);
    }
    if (assert) {
      BOOST_TEST_INFO("pair " << pair.id << " under " << Policy::name);
      BOOST_TEST(ok);
    }
    misses += !ok;
  }
  return misses;
}

}  // namespace

BOOST_AUTO_TEST_CASE(contact3d_reference_penetrations) {
  BOOST_TEST_REQUIRE(rt::contact3d_pairs().size() == 132u);
  double filtered = 0, exact = 0, checked = 0, unchecked = 0;
  check_reference_penetrations<rk::Filtered>(true, filtered);
  check_reference_penetrations<rk::Exact>(true, exact);
  check_reference_penetrations<rk::Checked>(true, checked);
  BOOST_TEST_MESSAGE("contact3d: largest |depth - reference| / scale: Filtered " << filtered << ", Exact " << exact);
  BOOST_TEST_MESSAGE("contact3d: Float's penetration differs from the reference on "
                     << check_reference_penetrations<rk::Float>(false, unchecked) << " of 132 pairs");
}

// Moving tp by (1 + k) depth * normal must give `separate`, by (1 - k) depth * normal
// `overlap`, under the exact verdict. The moved vertices are rounded to doubles, each by at
// most half an ulp of the largest coordinate m, which perturbs the pair's true minimum
// translation by at most sqrt(3)/2 ulp(m) <= 2^-52 m; a normal off by an angle t changes the
// gap only by depth t^2 / 2 (t < 1e-12 here). So k = 256 * 2^-52 m / depth (at least 1e-9)
// decides both sides soundly; pairs needing k > 1e-3 (depths of 2^-30 and less next to
// metre-sized coordinates) are skipped, as are pairs whose moved faces are no longer exactly
// planar (make() rejects them).
template <class Policy>
int check_translation_property() {
  int tested = 0;
  for (const auto& pair : rt::contact3d_pairs()) {
    const auto p = rk::penetration<Policy>(pair.cp, pair.tp);
    if (!p) continue;
    double m = 0;
    for (const auto* block : {&pair.cp, &pair.tp}) {
      for (const Point3& v : block->vertices()) m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    }
    const double k = std::max(1e-9, 256 * 0x1p-52 * m / p->depth);
    if (k > 1e-3) continue;
    const auto moved = [&](double factor) {
      const double t = factor * p->depth;
      return rt::translated(pair.tp, {t * p->normal.x, t * p->normal.y, t * p->normal.z});
    };
    try {
      const ConvexPolyhedron beyond = moved(1 + k), short_of = moved(1 - k);
      BOOST_TEST_CONTEXT("pair " << pair.id << " under " << Policy::name << ", k = " << k) {
        BOOST_TEST((rk::classify_overlap<rk::Exact>(pair.cp, beyond) == rk::Overlap::separate));
        BOOST_TEST((rk::classify_overlap<rk::Exact>(pair.cp, short_of) == rk::Overlap::overlap));
      }
      ++tested;
    } catch (const rk::InvalidPolyhedron&) {
      continue;
    }
  }
  return tested;
}

BOOST_AUTO_TEST_CASE(translation_by_depth_touches) {
  const int filtered = check_translation_property<rk::Filtered>();
  const int exact = check_translation_property<rk::Exact>();
  BOOST_TEST_MESSAGE("translation property checked on " << filtered << " (Filtered) and " << exact
                                                        << " (Exact) contact3d pairs");
  BOOST_TEST(filtered >= 20);
  BOOST_TEST(exact >= 20);
}
