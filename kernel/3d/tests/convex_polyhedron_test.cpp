#define BOOST_TEST_MODULE kernel3d_convex_polyhedron
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

// ConvexPolyhedron::make accepts exactly the convex polyhedra it documents and names the block,
// face and vertex of every violation. Each bad input is a unit cube with one defect, so the
// expected reason and position are known by construction.

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rk::InvalidPolyhedron;
using rk::Point3;
using Reason = InvalidPolyhedron::Reason;

namespace {

std::vector<Point3> cube_vertices() {
  return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}

// Counter-clockwise seen from outside.
std::vector<ConvexPolyhedron::Face> cube_faces() {
  return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
}

void expect_invalid(std::vector<Point3> vertices, std::vector<ConvexPolyhedron::Face> faces, Reason reason,
                    std::ptrdiff_t face, std::ptrdiff_t vertex, const std::string& words) {
  try {
    static_cast<void>(ConvexPolyhedron::make("block 7", std::move(vertices), std::move(faces)));
    BOOST_FAIL("accepted an invalid polyhedron (expected: " << words << ")");
  } catch (const InvalidPolyhedron& e) {
    const std::string what = e.what();
    BOOST_TEST_INFO(what);
    BOOST_TEST((e.reason() == reason));
    BOOST_TEST_INFO(what);
    BOOST_TEST(e.face() == face);
    BOOST_TEST_INFO(what);
    BOOST_TEST(e.vertex() == vertex);
    BOOST_TEST(e.block() == "block 7");
    BOOST_TEST(what.find("polyhedron 'block 7'") != std::string::npos);
    BOOST_TEST_INFO(what);
    BOOST_TEST(what.find(words) != std::string::npos);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(valid_cube_and_tetrahedron) {
  const ConvexPolyhedron cube = ConvexPolyhedron::make("cube", cube_vertices(), cube_faces());
  BOOST_TEST(cube.size() == 8u);
  BOOST_TEST(cube.faces().size() == 6u);
  BOOST_TEST(cube.edges().size() == 12u);  // V - E + F = 2
  for (const auto& [a, b] : cube.edges()) BOOST_TEST(a < b);
  const ConvexPolyhedron tet =
      ConvexPolyhedron::make("tet", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  BOOST_TEST(tet.edges().size() == 6u);
  // Far from the origin with bit-heavy coordinates: exact decisions, no tolerance.
  std::vector<Point3> far = cube_vertices();
  for (Point3& p : far) p = {p.x * 0.1 + 1e6, p.y * 0.1 - 1e6, p.z * 0.1 + 1e6};
  BOOST_CHECK_NO_THROW(ConvexPolyhedron::make("far", far, cube_faces()));
}

BOOST_AUTO_TEST_CASE(bad_vertices_are_named) {
  expect_invalid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, Reason::too_few_vertices, -1, -1, "at least 4 vertices");
  auto v = cube_vertices();
  v[5].y = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(v, cube_faces(), Reason::non_finite, -1, 5, "finite");
  v = cube_vertices();
  v[6] = v[2];
  expect_invalid(v, cube_faces(), Reason::repeated_vertex, -1, 6, "repeats vertex 2");
}

BOOST_AUTO_TEST_CASE(bad_faces_are_named) {
  auto f = cube_faces();
  f[3] = {1, 2};
  expect_invalid(cube_vertices(), f, Reason::bad_face, 3, -1, "at least 3 vertices");
  f = cube_faces();
  f[2][1] = 9;
  expect_invalid(cube_vertices(), f, Reason::bad_face, 2, -1, "out of range");
  // An open face set: the top face left out.
  f = cube_faces();
  f.erase(f.begin() + 1);
  // (The first unmatched edge in index order is 4 -> 7, of the left face, now face 4.)
  expect_invalid(cube_vertices(), f, Reason::not_closed, 4, 4, "do not close");
  // The bottom face given clockwise: its edges run the same way as its neighbours'.
  f = cube_faces();
  f[0] = {0, 1, 2, 3};
  expect_invalid(cube_vertices(), f, Reason::not_closed, 2, 0, "same direction");
  // A vertex on no face.
  auto v = cube_vertices();
  v.push_back({0.5, 0.5, 0.5});
  expect_invalid(v, cube_faces(), Reason::unused_vertex, -1, 8, "on no face");
}

BOOST_AUTO_TEST_CASE(bad_geometry_is_named) {
  // A top vertex lifted by 1e-6 of the unit cube's size, 1000 times the planarity tolerance:
  // the top face, the first face through it, is refused. Every vertex of a square with one
  // corner lifted by h lies h/4 from the mean plane, so any of them may be named.
  auto v = cube_vertices();
  v[7].z = 1.0 + 1e-6;
  try {
    static_cast<void>(ConvexPolyhedron::make("block 7", v, cube_faces()));
    BOOST_FAIL("accepted a face bent by 1e-6");
  } catch (const InvalidPolyhedron& e) {
    BOOST_TEST_INFO(e.what());
    BOOST_TEST((e.reason() == Reason::not_planar));
    BOOST_TEST(e.face() == 1);
    BOOST_TEST((e.vertex() >= 4 && e.vertex() <= 7));
    BOOST_TEST(std::string(e.what()).find("off the face's mean plane") != std::string::npos);
  }
  // A pyramid whose apex lies on the outer side of its base: the base, counter-clockwise seen
  // from above, has its outward normal towards the apex.
  const std::vector<Point3> pyramid{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 1}};
  const std::vector<ConvexPolyhedron::Face> roof{{0, 1, 2, 3}, {0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}};
  expect_invalid(pyramid, roof, Reason::not_convex, 0, 4, "above the face's plane");
  // Two coplanar triangles instead of one square face: a vertex on a face's plane, not on it.
  auto f = cube_faces();
  f[1] = {4, 5, 6};
  f.push_back({4, 6, 7});
  expect_invalid(cube_vertices(), f, Reason::not_convex, 1, 7, "merge coplanar faces");
  // A vertex in the middle of an edge: the face goes straight on there.
  std::vector<Point3> with_midpoint{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0, 0}};
  const std::vector<ConvexPolyhedron::Face> tet_faces{{0, 2, 1, 4}, {0, 4, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  expect_invalid(with_midpoint, tet_faces, Reason::not_convex, 0, 4, "straight on");
  // Every vertex in one plane: zero volume.
  const std::vector<Point3> flat{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  expect_invalid(flat, {{0, 1, 2, 3}, {3, 2, 1, 0}}, Reason::not_convex, 0, -1, "zero volume");
}

// Faces planar only to rounding are split by the exact hull into exactly planar facets.
BOOST_AUTO_TEST_CASE(faces_bent_by_rounding_are_split_into_hull_facets) {
  // One ulp up at vertex 7 (0, 1, 1) bends the top face only: the back (y = 1) and left (x = 0)
  // faces through it stay exactly planar. The top becomes two triangles, the other five stay
  // whole: 7 facets, and by Euler's formula 8 + 7 - 2 = 13 edges.
  auto v = cube_vertices();
  v[7].z = std::nextafter(1.0, 2.0);
  const ConvexPolyhedron bent = ConvexPolyhedron::make("bent", v, cube_faces());
  BOOST_TEST(bent.faces().size() == 7u);
  BOOST_TEST(bent.edges().size() == 13u);
  BOOST_TEST(bent.input_faces().size() == 6u);
  std::vector<int> facets_per_face(6, 0);
  for (std::size_t f = 0; f < bent.faces().size(); ++f) {
    const auto& facet = bent.faces()[f];
    const auto& face = bent.input_faces()[bent.input_face(f)];
    ++facets_per_face[bent.input_face(f)];
    for (const std::uint32_t i : facet) BOOST_TEST((std::find(face.begin(), face.end(), i) != face.end()));
  }
  BOOST_TEST(facets_per_face == (std::vector<int>{1, 2, 1, 1, 1, 1}), boost::test_tools::per_element());
  // The lifted vertex is above the plane of the other three top vertices, so the hull has a
  // ridge through it: the top folds along the diagonal 5-7 into (4, 5, 7) and (5, 6, 7).
  for (const ConvexPolyhedron::Face& facet : {ConvexPolyhedron::Face{4, 5, 7}, ConvexPolyhedron::Face{5, 6, 7}}) {
    BOOST_TEST((std::find(bent.faces().begin(), bent.faces().end(), facet) != bent.faces().end()));
  }
  const auto has_edge = [&](std::uint32_t a, std::uint32_t b) {
    return std::find(bent.edges().begin(), bent.edges().end(), ConvexPolyhedron::Edge{a, b}) != bent.edges().end();
  };
  BOOST_TEST(has_edge(5, 7));
  BOOST_TEST(!has_edge(4, 6));
}

// A rotated cube, near the origin and 10^6 m away: rounding the rotated coordinates leaves its
// faces planar only to within a few ulps, which the tolerance accepts; moved() keeps the faces
// as given while the facets follow the exact hull of the new coordinates.
BOOST_AUTO_TEST_CASE(rotated_and_moved_blocks_keep_their_faces) {
  const ConvexPolyhedron cube = ConvexPolyhedron::make("cube", cube_vertices(), cube_faces());
  for (const double offset : {0.0, 1e6}) {
    // A rotation by 0.7 rad about the axis (1, 2, 3)/sqrt(14) (Rodrigues' formula).
    const double c = std::cos(0.7), s = std::sin(0.7), n = std::sqrt(14.0);
    const double x = 1 / n, y = 2 / n, z = 3 / n;
    const double r[3][3] = {{c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s},
                            {y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s},
                            {z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)}};
    std::vector<Point3> turned;
    for (const Point3& p : cube.vertices()) {
      turned.push_back({r[0][0] * p.x + r[0][1] * p.y + r[0][2] * p.z + offset,
                        r[1][0] * p.x + r[1][1] * p.y + r[1][2] * p.z - offset,
                        r[2][0] * p.x + r[2][1] * p.y + r[2][2] * p.z + offset});
    }
    BOOST_TEST_INFO("offset " << offset);
    const ConvexPolyhedron moved = cube.moved(turned);
    BOOST_TEST(moved.size() == 8u);
    BOOST_TEST((moved.input_faces().size() == 6u && std::equal(moved.input_faces().begin(), moved.input_faces().end(),
                                                                 cube.input_faces().begin())));
    // Every facet lies in one face, and every face keeps at least one facet.
    std::vector<bool> covered(6, false);
    for (std::size_t f = 0; f < moved.faces().size(); ++f) covered[moved.input_face(f)] = true;
    BOOST_TEST((std::count(covered.begin(), covered.end(), true) == 6));
    // Euler's formula holds for whatever split the hull chose.
    BOOST_TEST(moved.size() + moved.faces().size() == moved.edges().size() + 2);
  }
  // Moving a vertex 1e-3 off its faces is refused, naming the block.
  auto v = cube_vertices();
  v[2].x += 1e-3;
  BOOST_CHECK_THROW(static_cast<void>(cube.moved(v)), InvalidPolyhedron);
}
