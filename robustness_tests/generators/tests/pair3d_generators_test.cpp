#define BOOST_TEST_MODULE robustness_pair3d_generators
#include "rockcontact/generators/pair3d_generators.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/testing/seed.hpp"

// The 3D generators: the hull against a closed form (a cube with redundant points on its
// faces, edges and inside), determinism, and, for every pair of every family, validity (a
// ConvexPolyhedron was made) and the separating-plane fact each exact construction rests on,
// measured back from the blocks' coordinates (exact comparisons of doubles): touching pairs
// have a in {coordinate <= 0} and b in {coordinate >= 0} along the construction's axis with
// both reaching 0; a gap puts b strictly above; a push puts b strictly below 0 somewhere.
// Whether the touching pair really meets, and the verdict of the rest, is the campaign's
// check (robustness_table3d: the Exact verdict against `expected`).

namespace rb = rockcontact::robustness;
namespace rk = rockcontact::kernel;
using rb::Family3d;
using rk::Point3;

namespace {

bool same(const rk::ConvexPolyhedron& p, const rk::ConvexPolyhedron& q) {
  return std::equal(p.vertices().begin(), p.vertices().end(), q.vertices().begin(), q.vertices().end()) &&
         std::equal(p.faces().begin(), p.faces().end(), q.faces().begin(), q.faces().end());
}

double coordinate(const Point3& p, int axis) { return axis == 0 ? p.x : p.z; }

double extreme(const rk::ConvexPolyhedron& p, int axis, bool max) {
  double best = max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (const Point3& v : p.vertices()) best = max ? std::max(best, coordinate(v, axis)) : std::min(best, coordinate(v, axis));
  return best;
}

}  // namespace

BOOST_AUTO_TEST_CASE(hull_of_a_cube_with_redundant_points) {
  std::vector<Point3> points;
  for (double x : {0.0, 1.0}) {
    for (double y : {0.0, 1.0}) {
      for (double z : {0.0, 1.0}) points.push_back({x, y, z});
    }
  }
  // Face centres, edge midpoints, the centre and a repeated corner: none is a hull corner.
  for (const Point3& p : std::vector<Point3>{{0.5, 0.5, 0}, {0.5, 0.5, 1}, {0, 0.5, 0.5}, {1, 0.5, 0.5}, {0.5, 0, 0.5},
                                             {0.5, 1, 0.5}, {0.5, 0, 0}, {1, 1, 0.5}, {0, 0.5, 1}, {0.5, 0.5, 0.5},
                                             {1, 1, 1}, {0.25, 0, 0.75}}) {
    points.push_back(p);
  }
  const auto cube = rb::convex_hull3("cube", points);
  BOOST_REQUIRE(cube.has_value());
  BOOST_TEST(cube->size() == 8u);
  BOOST_TEST(cube->faces().size() == 6u);
  for (const auto& face : cube->faces()) BOOST_TEST(face.size() == 4u);
  // Volume and centroid of the unit cube (exact in double: dyadic sums).
  const rk::Moments3 m = rk::moments(*cube);
  BOOST_TEST(m.volume == 1.0);
  BOOST_TEST(m.centroid().z == 0.5);

  const std::vector<Point3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.25, 0}};
  BOOST_TEST(!rb::convex_hull3("flat", flat).has_value());
  const std::vector<Point3> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0.5, 0.5, 0.5}};
  BOOST_TEST(!rb::convex_hull3("line", line).has_value());
}

BOOST_AUTO_TEST_CASE(deterministic) {
  for (Family3d f : rb::all_families3d) {
    const rb::PolyhedronPair p = rb::generate_pair3d(f, 7, 12);
    const rb::PolyhedronPair q = rb::generate_pair3d(f, 7, 12);
    const rb::PolyhedronPair r = rb::generate_pair3d(f, 7, 13);
    BOOST_TEST_INFO(p.recipe);
    BOOST_TEST((same(p.a, q.a) && same(p.b, q.b) && p.recipe == q.recipe && p.expected == q.expected));
    BOOST_TEST(!(same(p.a, r.a) && same(p.b, r.b)));
    BOOST_TEST((rb::parse_family3d(rb::to_string(f)) == f));
  }
}

BOOST_AUTO_TEST_CASE(construction_facts) {
  const std::uint64_t seed = rockcontact::testing::seed_for("construction_facts", 20261125);
  for (Family3d f : rb::all_families3d) {
    std::array<int, 3> verdicts{};
    int with_expected = 0;
    for (std::uint64_t i = 0; i < 200; ++i) {
      const rb::PolyhedronPair p = rb::generate_pair3d(f, seed, i);
      BOOST_TEST_INFO(p.recipe);
      BOOST_TEST((p.family == f));
      BOOST_TEST(p.a.size() >= 4u);
      BOOST_TEST(p.b.size() >= 4u);
      if (!p.expected) continue;
      ++with_expected;
      ++verdicts[static_cast<int>(*p.expected)];
      // The axis-plane constructions (not the copied face, not the shifted meta pairs).
      if (f == Family3d::offset_1e6 || p.recipe.find("copied") != std::string::npos) continue;
      const int axis = f == Family3d::short_edges ? 0 : 2;
      const double top = extreme(p.a, axis, true);
      const double bottom = extreme(p.b, axis, false);
      const double plane = f == Family3d::short_edges ? top : 0.0;
      BOOST_TEST_INFO(p.recipe);
      BOOST_TEST(top == plane);
      switch (*p.expected) {
        case rk::Overlap::touch: BOOST_TEST(bottom == plane); break;
        case rk::Overlap::separate: BOOST_TEST(bottom > plane); break;
        case rk::Overlap::overlap: BOOST_TEST(bottom < plane); break;
      }
    }
    BOOST_TEST_MESSAGE(rb::to_string(f) << ": " << with_expected << " of 200 with a verdict (separate " << verdicts[0]
                                        << ", touch " << verdicts[1] << ", overlap " << verdicts[2] << ")");
    const bool exact_family = f != Family3d::random && f != Family3d::rotated && f != Family3d::deformed;
    BOOST_TEST_INFO(rb::to_string(f));
    BOOST_TEST((with_expected > 0) == exact_family);
    if (exact_family && f != Family3d::offset_1e6) BOOST_TEST(verdicts[1] > 0);
  }
}
