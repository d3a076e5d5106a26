#define BOOST_TEST_MODULE kernel3d_plane_cut
#include "rockcontact/kernel/3d/plane_cut.hpp"

#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "polyhedron_checks.hpp"
#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/seed.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

// Clipping and cutting by a plane: closed forms on the unit cube (a general cut, cuts through
// vertices, an edge, a face, planes that only touch or miss, a cut through implicit vertices of
// an earlier cut), every piece checked valid (closed oriented 2-manifold, each vertex exactly on
// its faces' planes and on or below the others); and exact volume conservation: a polyhedron
// cut successively by several planes, including planes through its vertices and edges and
// through the implicit vertices of earlier cuts, whose pieces' exact rational volumes must sum
// to the original's exactly.

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rockcontact::testing::box;
using rk::HalfspacePolyhedron;
using rk::Plane3;
using rk::Point3;

namespace {

mpq_class exact_volume(const HalfspacePolyhedron& h) { return mpq_class(rk::detail::exact_volume_string(h)); }

std::size_t implicit_count(const HalfspacePolyhedron& h) {
  return static_cast<std::size_t>(
      std::count_if(h.vertices().begin(), h.vertices().end(), [](const auto& v) { return !v.input; }));
}

// Cuts under Checked (each sign compared with its exact evaluation), checks both pieces and the
// exact volumes, and that Filtered and Exact give the same pieces.
std::pair<HalfspacePolyhedron, HalfspacePolyhedron> check_cut(const HalfspacePolyhedron& p, const Plane3& plane,
                                                                const mpq_class& below, const mpq_class& above) {
  auto pieces = rk::cut_by_plane<rk::Checked>(p, plane);
  rockcontact::testing::check_valid(pieces.first);
  rockcontact::testing::check_valid(pieces.second);
  BOOST_TEST(exact_volume(pieces.first) == below);
  BOOST_TEST(exact_volume(pieces.second) == above);
  BOOST_TEST(pieces.first.volume<rk::Exact>() == below.get_d());
  BOOST_TEST(std::fabs(pieces.first.volume<rk::Filtered>() - below.get_d()) <= 1e-15);
  const auto filtered = rk::cut_by_plane<rk::Filtered>(p, plane);
  BOOST_TEST((filtered.first.faces().size() == pieces.first.faces().size() &&
              filtered.first.vertices().size() == pieces.first.vertices().size()));
  BOOST_TEST(rk::clip<rk::Exact>(p, plane).vertices().size() == pieces.first.vertices().size());
  return pieces;
}

}  // namespace

BOOST_AUTO_TEST_CASE(cube_cuts_in_closed_form) {
  const HalfspacePolyhedron cube(box("cube", {0, 0, 0}, {1, 1, 1}));
  // x + y + z = 1.5: two congruent halves of 1/2, the section a regular hexagon of implicit
  // vertices, the permutations of (1, 0.5, 0).
  for (const Plane3& plane : {Plane3::from_coefficients(1, 1, 1, 1.5),
                              Plane3::through({1.5, 0, 0}, {0, 1.5, 0}, {0, 0, 1.5})}) {
    const auto [below, above] = check_cut(cube, plane, mpq_class(1, 2), mpq_class(1, 2));
    BOOST_TEST(implicit_count(below) == 6u);
    BOOST_TEST(below.faces().back().loop.size() == 6u);
    std::vector<Point3> hexagon;
    const auto coordinates = below.vertex_coordinates<rk::Exact>();
    for (std::uint32_t v : below.faces().back().loop) hexagon.push_back(coordinates[v]);
    for (const Point3& x : hexagon) {
      std::array<double, 3> c{x.x, x.y, x.z};
      std::sort(c.begin(), c.end());
      BOOST_TEST((c == std::array<double, 3>{0, 0.5, 1}));
    }
  }
  // x + y + z = 1 through three vertices: a corner tetrahedron of 1/6, no new vertex.
  {
    const auto [below, above] = check_cut(cube, Plane3::from_coefficients(1, 1, 1, 1), mpq_class(1, 6), mpq_class(5, 6));
    BOOST_TEST(implicit_count(below) + implicit_count(above) == 0u);
    BOOST_TEST(below.vertices().size() == 4u);
    BOOST_TEST(above.vertices().size() == 7u);
  }
  // x = y through two opposite edges: two prisms of 1/2, no new vertex.
  {
    const auto [below, above] = check_cut(cube, Plane3::from_coefficients(1, -1, 0, 0), mpq_class(1, 2), mpq_class(1, 2));
    BOOST_TEST(implicit_count(below) + implicit_count(above) == 0u);
    BOOST_TEST(below.vertices().size() == 6u);
  }
  // The plane of a face, from either side; planes touching a vertex or an edge; planes missing.
  const mpq_class one(1), zero(0);
  check_cut(cube, Plane3::from_coefficients(0, 0, 1, 1), one, zero);
  check_cut(cube, Plane3::from_coefficients(0, 0, 1, 0), zero, one);
  check_cut(cube, Plane3::from_coefficients(0, 0, -1, 0), one, zero);
  check_cut(cube, Plane3::from_coefficients(1, 1, 1, 3), one, zero);
  check_cut(cube, Plane3::from_coefficients(1, 1, 0, 0), zero, one);
  check_cut(cube, Plane3::from_coefficients(0, 0, 1, 5), one, zero);
  check_cut(cube, Plane3::from_coefficients(0, 0, 1, -1), zero, one);
  BOOST_TEST((rk::clip<rk::Exact>(cube, Plane3::from_coefficients(0, 0, 1, 1)).faces().size() == 6u));
  BOOST_TEST(rk::clip<rk::Exact>(cube, Plane3::from_coefficients(1, 1, 0, 2)).faces().size() == 6u);
}

// x = 1/2 makes implicit vertices (1/2, y, z); the plane x + y = 1/2 then runs through the
// implicit edge y = 0 of the left half, so its two implicit vertices are kept as they are (no
// new vertex on that edge) and the pieces are a triangular prism of 1/8 and the rest, 3/8.
BOOST_AUTO_TEST_CASE(cut_through_implicit_vertices) {
  const HalfspacePolyhedron cube(box("cube", {0, 0, 0}, {1, 1, 1}));
  const HalfspacePolyhedron left = rk::clip<rk::Checked>(cube, Plane3::from_coefficients(1, 0, 0, 0.5));
  BOOST_TEST(implicit_count(left) == 4u);
  const auto [below, above] =
      check_cut(left, Plane3::from_coefficients(1, 1, 0, 0.5), mpq_class(1, 8), mpq_class(3, 8));
  BOOST_TEST(below.vertices().size() == 6u);
  BOOST_TEST(implicit_count(below) == 4u);  // (1/2, 0, z) kept, (0, 1/2, z) new
  // The same through points: the plane through (1/2, 0, 0), (0, 1/2, 0), (0, 1/2, 1).
  check_cut(left, Plane3::through({0.5, 0, 0}, {0, 0.5, 0}, {0, 0.5, 1}), mpq_class(1, 8), mpq_class(3, 8));
  // Cutting again by the plane that made the implicit vertices: a face on the plane.
  check_cut(left, Plane3::from_coefficients(1, 0, 0, 0.5), mpq_class(1, 2), mpq_class(0));
}

// Exact conservation under successive cuts: every piece is cut by every plane in turn (a binary
// space partition); the exact volumes of the final pieces sum to the original's.
namespace {

void check_conservation(const HalfspacePolyhedron& original, const std::vector<Plane3>& planes) {
  std::vector<HalfspacePolyhedron> pieces{original};
  for (const Plane3& plane : planes) {
    std::vector<HalfspacePolyhedron> next;
    for (const HalfspacePolyhedron& piece : pieces) {
      auto [below, above] = rk::cut_by_plane<rk::Checked>(piece, plane);
      if (!below.empty()) next.push_back(std::move(below));
      if (!above.empty()) next.push_back(std::move(above));
    }
    pieces = std::move(next);
  }
  mpq_class sum = 0;
  double filtered = 0;
  for (const HalfspacePolyhedron& piece : pieces) {
    rockcontact::testing::check_valid(piece);
    sum += exact_volume(piece);
    filtered += piece.volume<rk::Filtered>();
  }
  const mpq_class total = exact_volume(original);
  BOOST_TEST(sum == total);
  // Filtered's rounded volumes: each within a few ulps of its fan terms (unit scale).
  BOOST_TEST(std::fabs(filtered - total.get_d()) <= 1e-12 * static_cast<double>(pieces.size()));
  BOOST_TEST_MESSAGE("conservation: " << pieces.size() << " pieces");
}

}  // namespace

BOOST_AUTO_TEST_CASE(exact_volume_conservation) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("exact_volume_conservation", 20261128));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Point3 o : {Point3{0, 0, 0}, Point3{0x1p20, -0x1p20, 0x1p20}}) {
    const ConvexPolyhedron p = box("box", o, {o.x + 1, o.y + 0.75, o.z + 1.25});
    const auto at = [&](double x, double y, double z) { return Point3{o.x + x, o.y + y, o.z + z}; };
    std::vector<Plane3> planes{
        Plane3::through(p[0], p[2], p[5]),                   // through three vertices
        Plane3::through(p[0], p[4], at(0.5, 0.75, 0.3)),     // through an edge
        Plane3::from_coefficients(1, 0, 0, o.x + 0.5),       // x = 1/2: implicit vertices
        Plane3::through(at(0.5, 0, 0), at(0.5, 0.75, 1.25), at(0, 0.2, 0.7)),  // through them
        Plane3::from_coefficients(0, 1, 1, o.y + o.z + 1.0),
    };
    for (int i = 0; i < 3; ++i) {
      planes.push_back(Plane3::through(at(0.5 + 0.5 * u(rng), 0.375 + 0.375 * u(rng), 0.625 + 0.625 * u(rng)),
                                       at(0.5 + 0.5 * u(rng), 0.375 + 0.375 * u(rng), 0.625 + 0.625 * u(rng)),
                                       at(0.5 + 0.5 * u(rng), 0.375 + 0.375 * u(rng), 0.625 + 0.625 * u(rng))));
    }
    check_conservation(HalfspacePolyhedron(p), planes);
  }
  // A random tetrahedron cut by planes through its vertices, edges and random points.
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<Point3> v{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)},
                          {u(rng), u(rng), u(rng)}};
    if (rk::orient3d<rk::Exact>(v[0], v[1], v[2], v[3]) == rk::Sign::negative) std::swap(v[1], v[2]);
    const ConvexPolyhedron t = ConvexPolyhedron::make("tet", v, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
    const Point3 m{(v[0].x + v[1].x) / 2, (v[0].y + v[1].y) / 2, (v[0].z + v[1].z) / 2};
    const Point3 r{u(rng), u(rng), u(rng)};
    check_conservation(HalfspacePolyhedron(t), {Plane3::through(v[0], v[1], r), Plane3::through(v[2], v[3], m),
                                                Plane3::through(m, r, {u(rng), u(rng), u(rng)}),
                                                Plane3::from_coefficients(u(rng), u(rng), u(rng), u(rng) * 0.1)});
  }
}
