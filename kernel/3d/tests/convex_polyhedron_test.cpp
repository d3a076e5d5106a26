#define BOOST_TEST_MODULE kernel3d_convex_polyhedron
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

#include <boost/test/unit_test.hpp>

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
  // A top vertex lifted by one ulp: the top face is not planar.
  auto v = cube_vertices();
  v[7].z = std::nextafter(1.0, 2.0);
  expect_invalid(v, cube_faces(), Reason::not_planar, 1, 7, "off the plane");
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
