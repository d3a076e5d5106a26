#define BOOST_TEST_MODULE kernel3d_overlap
#include "rockcontact/kernel/3d/overlap.hpp"

#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"
#include "rockcontact/kernel/3d/detail/separating_plane.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/testing/contact3d.hpp"
#include "rockcontact/testing/seed.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

// The overlap verdict of two convex polyhedra against closed forms (unit cubes moved by exact
// offsets, so each contact's kind is known: face on face, edge on face, edge across edge,
// vertex on vertex, apart by 2^-40) and against the independent contact3d reference data
// (exactly computed statuses of 132 adversarial pairs). A verdict is combinatorial: the staged
// policies must give the expected one exactly; Float's disagreements are counted.

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rockcontact::testing::box;
using rockcontact::testing::unit_cube_at;
using rockcontact::testing::octahedron;
using rk::Overlap;
using rk::Point3;

namespace {

template <class Policy>
void check_all_orders(const ConvexPolyhedron& a, const ConvexPolyhedron& b, Overlap expected) {
  BOOST_TEST_INFO(a.name() << " / " << b.name() << " under " << Policy::name);
  BOOST_TEST((rk::classify_overlap<Policy>(a, b) == expected));
  BOOST_TEST_INFO(b.name() << " / " << a.name() << " under " << Policy::name);
  BOOST_TEST((rk::classify_overlap<Policy>(b, a) == expected));
}

void check_staged(const ConvexPolyhedron& a, const ConvexPolyhedron& b, Overlap expected) {
  check_all_orders<rk::Filtered>(a, b, expected);
  check_all_orders<rk::Exact>(a, b, expected);
  check_all_orders<rk::Checked>(a, b, expected);
}

}  // namespace

BOOST_AUTO_TEST_CASE(cubes_in_closed_form) {
  const ConvexPolyhedron a = unit_cube_at("a", {0, 0, 0});
  const double gap = 0x1p-40;
  check_staged(a, unit_cube_at("half inside", {0.5, 0.25, 0.125}), Overlap::overlap);
  check_staged(a, unit_cube_at("same", {0, 0, 0}), Overlap::overlap);
  check_staged(a, unit_cube_at("face on face", {1, 0, 0}), Overlap::touch);
  check_staged(a, unit_cube_at("face on face, shifted", {0.3, 0.6, 1}), Overlap::touch);
  check_staged(a, unit_cube_at("edge on edge", {1, 1, 0.5}), Overlap::touch);
  check_staged(a, unit_cube_at("vertex on vertex", {1, 1, 1}), Overlap::touch);
  check_staged(a, unit_cube_at("apart by 2^-40", {1 + gap, 0.5, 0.5}), Overlap::separate);
  check_staged(a, unit_cube_at("overlap by 2^-40", {1 - gap, 0.5, 0.5}), Overlap::overlap);
  check_staged(a, unit_cube_at("diagonal, apart", {1 + gap, 1, 1}), Overlap::separate);
  // An octahedron's vertex on the cube's top face, on its edge, and just above.
  check_staged(a, octahedron("vertex on face", {0.5, 0.5, 1.5}, 0.5), Overlap::touch);
  check_staged(a, octahedron("vertex on edge", {0.5, 1.5, 1}, 0.5), Overlap::touch);
  check_staged(a, octahedron("vertex above face", {0.5, 0.5, 1.5 + gap}, 0.5), Overlap::separate);
  // Far from the origin: 1e6 m offsets with bit-heavy sizes, face on face exactly.
  const Point3 o{1e6 + 0.1, -1e6 + 0.3, 1e6 + 0.7};
  const ConvexPolyhedron far = box("far", o, {o.x + 0.3, o.y + 0.7, o.z + 0.1});
  check_staged(far, box("far, on top", {o.x + 0.1, o.y + 0.2, o.z + 0.1}, {o.x + 0.2, o.y + 0.3, o.z + 0.9}),
               Overlap::touch);
}

// Crossing edges: a cube and a copy rotated 90 degrees about an axis through one of its edges
// would share the edge; instead, a tetrahedron whose edge crosses the cube's top edge exactly.
BOOST_AUTO_TEST_CASE(crossing_edges_touch) {
  const ConvexPolyhedron a = unit_cube_at("a", {0, 0, 0});
  // Edge from (0.5, 0.75, 1.25)... the tetrahedron's lowest edge runs from (0.5, 1.5, 0.5) to
  // (0.5, 0.5, 1.5): it crosses the cube's top back edge y = 1, z = 1 at x = 0.5 and otherwise
  // stays outside the cube (y + z = 2 along it, above the cube's y + z <= 2).
  const ConvexPolyhedron t = ConvexPolyhedron::make(
      "tet", {{0.5, 1.5, 0.5}, {0.5, 0.5, 1.5}, {0.0, 2.0, 2.0}, {1.0, 2.0, 2.0}},
      {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
  check_staged(a, t, Overlap::touch);
}

BOOST_AUTO_TEST_CASE(contact3d_reference_statuses) {
  const auto& pairs = rockcontact::testing::contact3d_pairs();
  BOOST_TEST_REQUIRE(pairs.size() == 132u);
  int float_wrong = 0;
  for (const auto& pair : pairs) {
    const std::string expected = pair.expected.at("status").get<std::string>();
    BOOST_TEST_CONTEXT("pair " << pair.id) {
      BOOST_TEST(std::string(rk::to_string(rk::classify_overlap<rk::Filtered>(pair.cp, pair.tp))) == expected);
      BOOST_TEST(std::string(rk::to_string(rk::classify_overlap<rk::Exact>(pair.cp, pair.tp))) == expected);
      BOOST_TEST(std::string(rk::to_string(rk::classify_overlap<rk::Checked>(pair.cp, pair.tp))) == expected);
      BOOST_TEST(std::string(rk::to_string(rk::classify_overlap<rk::Filtered>(pair.tp, pair.cp))) == expected);
    }
    float_wrong += std::string(rk::to_string(rk::classify_overlap<rk::Float>(pair.cp, pair.tp))) != expected;
  }
  BOOST_TEST_MESSAGE("contact3d: Float's verdict differs from the reference on " << float_wrong << " of "
                                                                                 << pairs.size() << " pairs");
}

// Properties on random tetrahedra (every face a triangle, so any four non-coplanar points make
// a valid block): the verdict is symmetric in the pair and unchanged by an exact translation
// (by 2^20 in each coordinate of dyadic points, where every sum is exact) and by an exact
// rotation (90 degrees about z: (x, y, z) -> (-y, x, z)); two tetrahedra sharing a face,
// their fourth vertices on opposite sides, touch; the same with one fourth vertex pushed
// through the shared face overlap. Checked must agree throughout (it throws otherwise).
namespace {

ConvexPolyhedron make_tet(const std::string& name, std::vector<Point3> v) {
  // Orient the faces outward: the face 0 2 1 must have vertex 3 below it, i.e.
  // orient3d(v0, v1, v2, v3) > 0; otherwise swap v1 and v2.
  if (rk::orient3d<rk::Exact>(v[0], v[1], v[2], v[3]) == rk::Sign::negative) std::swap(v[1], v[2]);
  return ConvexPolyhedron::make(name, std::move(v), {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

}  // namespace

BOOST_AUTO_TEST_CASE(random_tetrahedra_properties) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("random_tetrahedra_properties", 20261127));
  std::uniform_int_distribution<int> grid(-64, 64);
  const auto dyadic = [&] { return Point3{grid(rng) * 0x1p-5, grid(rng) * 0x1p-5, grid(rng) * 0x1p-5}; };
  const auto valid = [](const std::vector<Point3>& v) {
    return rk::orient3d<rk::Exact>(v[0], v[1], v[2], v[3]) != rk::Sign::zero;
  };
  const auto moved = [](std::vector<Point3> v, Point3 by) {
    for (Point3& p : v) p = {p.x + by.x, p.y + by.y, p.z + by.z};
    return v;
  };
  const auto rotated = [](std::vector<Point3> v) {
    for (Point3& p : v) p = {-p.y, p.x, p.z};
    return v;
  };
  std::array<int, 3> verdicts{};
  int float_wrong = 0, checked = 0;
  while (checked < 3000) {
    std::vector<Point3> va{dyadic(), dyadic(), dyadic(), dyadic()}, vb{dyadic(), dyadic(), dyadic(), dyadic()};
    if (!valid(va) || !valid(vb)) continue;
    // Every third pair shares a face: b's first three vertices are a's, b's apex mirrored.
    if (checked % 3 == 0) {
      vb = {va[0], va[1], va[2], {2 * va[0].x - va[3].x, 2 * va[0].y - va[3].y, 2 * va[0].z - va[3].z}};
    }
    const ConvexPolyhedron a = make_tet("a", va), b = make_tet("b", vb);
    const Overlap verdict = rk::classify_overlap<rk::Checked>(a, b);
    ++verdicts[static_cast<std::size_t>(verdict)];
    if (checked % 3 == 0) BOOST_TEST((verdict == Overlap::touch));
    BOOST_TEST((rk::classify_overlap<rk::Checked>(b, a) == verdict));
    const Point3 by{0x1p20, -0x1p20, 0x1p20};
    BOOST_TEST((rk::classify_overlap<rk::Filtered>(make_tet("a+", moved(va, by)), make_tet("b+", moved(vb, by))) ==
                verdict));
    BOOST_TEST((rk::classify_overlap<rk::Filtered>(make_tet("ra", rotated(va)), make_tet("rb", rotated(vb))) ==
                verdict));
    float_wrong += rk::classify_overlap<rk::Float>(a, b) != verdict;
    ++checked;
  }
  // The draw must reach all three verdicts, or the properties were not tested on them.
  BOOST_TEST(verdicts[0] > 0);
  BOOST_TEST(verdicts[1] >= 1000);
  BOOST_TEST(verdicts[2] > 0);
  BOOST_TEST_MESSAGE("random tetrahedra: " << verdicts[0] << " separate, " << verdicts[1] << " touch, "
                                           << verdicts[2] << " overlap; Float wrong on " << float_wrong);
}

namespace {

// The verdict over every candidate plane, no edge pair pruned: the definition the pruned
// classify_overlap must reproduce (overlap.cpp).
Overlap verdict_over_all_candidates(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  using rk::detail::Gap;
  bool touching = false;
  const auto weigh = [&](Gap gap) {
    touching |= gap == Gap::zero;
    return gap == Gap::positive;
  };
  for (const auto& face : a.faces()) {
    if (weigh(rk::detail::face_gap<rk::Exact>(a, face, b))) return Overlap::separate;
  }
  for (const auto& face : b.faces()) {
    if (weigh(rk::detail::face_gap<rk::Exact>(b, face, a))) return Overlap::separate;
  }
  for (const auto& ea : a.edges()) {
    for (const auto& eb : b.edges()) {
      if (weigh(rk::detail::edge_gap<rk::Exact>(a, ea, b, eb))) return Overlap::separate;
    }
  }
  return touching ? Overlap::touch : Overlap::overlap;
}

}  // namespace

// Pruning edge pairs on the Gauss map keeps exactly the verdict of all candidates: on the
// contact3d pairs (every kind of touch, near-parallel faces, rotated cubes) and on random
// dyadic tetrahedra, a third of them sharing a face, in both orders.
BOOST_AUTO_TEST_CASE(gauss_map_pruning_keeps_the_verdict) {
  for (const auto& pair : rockcontact::testing::contact3d_pairs()) {
    BOOST_TEST_INFO(pair.id);
    BOOST_TEST((rk::classify_overlap<rk::Filtered>(pair.cp, pair.tp) == verdict_over_all_candidates(pair.cp, pair.tp)));
  }
  std::mt19937_64 rng(rockcontact::testing::seed_for("gauss_map_pruning_keeps_the_verdict", 20261125));
  std::uniform_int_distribution<int> grid(-8, 8);
  const auto dyadic = [&] { return Point3{grid(rng) * 0.25, grid(rng) * 0.25, grid(rng) * 0.25}; };
  int checked = 0;
  while (checked < 2000) {
    std::vector<Point3> va{dyadic(), dyadic(), dyadic(), dyadic()}, vb{dyadic(), dyadic(), dyadic(), dyadic()};
    if (checked % 3 == 0) vb = {va[0], va[1], va[2], {2 * va[0].x - va[3].x, 2 * va[0].y - va[3].y, 2 * va[0].z - va[3].z}};
    if (rk::orient3d<rk::Exact>(va[0], va[1], va[2], va[3]) == rk::Sign::zero ||
        rk::orient3d<rk::Exact>(vb[0], vb[1], vb[2], vb[3]) == rk::Sign::zero) {
      continue;
    }
    const ConvexPolyhedron a = make_tet("a", va), b = make_tet("b", vb);
    BOOST_TEST((rk::classify_overlap<rk::Filtered>(a, b) == verdict_over_all_candidates(a, b)));
    BOOST_TEST((rk::classify_overlap<rk::Filtered>(b, a) == verdict_over_all_candidates(b, a)));
    ++checked;
  }
}
