#define BOOST_TEST_MODULE kernel_triangle_mesh
#include <boost/test/unit_test.hpp>

// mesh_polygon (triangle_mesh.hpp). Every mesh is checked against properties computed here,
// independently of CGAL (check_mesh):
//   - the input vertices are nodes 0..n-1, bit for bit;
//   - every triangle is strictly counter-clockwise (orientation<Filtered>, exact) and uses
//     valid node indices; every node is used by a triangle;
//   - conformity: no directed edge appears twice, every undirected edge is used by one or two
//     triangles (in opposite directions), and the edges used once are exactly the boundary
//     loop's edges, in the loop's direction. With the loop equal to the polygon's (subdivided)
//     boundary and every triangle positive, the triangles cover the polygon exactly once;
//   - the sum of the triangle areas equals the polygon's area (analytic, per case);
//   - the size bound: every edge satisfies (dx² + dy²) / max_edge² <= 1 in double, the very
//     expression CGAL's Delaunay_mesh_size_criteria_2 evaluates (with -ffp-contract=off in both
//     builds), so no slack; in real numbers an edge may exceed max_edge by at most the rounding
//     of that expression, a relative 2^-52 or so;
//   - the shape bound: every angle >= 20 degrees (CGAL's B = 0.125 means 20.70 degrees; atan2
//     errors are ~1e-15 rad, the rest is margin);
//   - the boundary loop starts at 0 and passes the vertices 0, 1, ..., n-1 in order; the nodes
//     between vertex i and i+1 lie on edge i in order along it: exactly (orientation<Filtered>
//     zero) on an axis-parallel edge, whose midpoints keep the constant coordinate exactly; on
//     an oblique edge within oblique_tolerance (below) of the line, since CGAL's midpoints are
//     rounded to double.
// Cases:
//   1. the unit square, max_edge 0.1;
//   2. the CDEM example's prism cross-section (0,0), (1,0), (0.5,0.8) and a non-convex L-shape;
//      element counts between the hard lower bound area / (max_edge² √3/4) (no triangle with
//      edges <= max_edge has more area than the equilateral one) and 4 times it;
//   3. bad input: each std::invalid_argument message names its vertex, edge or max_edge;
//   4. a square far from the origin, a polygon with a collinear (180 degree) vertex,
//      determinism.
// The test does not include CGAL.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/kernel/2d/predicates.hpp"
#include "rockcontact/kernel/2d/triangle_mesh.hpp"

namespace rk = rockcontact::kernel;
using rk::Point2;
using Polygon = std::vector<Point2>;
using Index = std::uint32_t;

namespace {

constexpr double pi = std::numbers::pi;

// What the checks measured, for the messages and the count bounds.
struct Measured {
  std::size_t triangles = 0;
  double min_angle_deg = 180.0;
  double max_edge_ratio = 0.0;  // largest (edge length / max_edge)
  double max_off_line = 0.0;    // largest distance of a boundary Steiner point from its edge's line
};

double cross(Point2 o, Point2 a, Point2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }
double dot(Point2 o, Point2 a, Point2 b) { return (a.x - o.x) * (b.x - o.x) + (a.y - o.y) * (b.y - o.y); }

// Distance allowed between a Steiner point of an oblique edge and the edge's line, relative to
// the largest coordinate magnitude C. A midpoint fl((a + b) / 2) rounds each coordinate by at
// most half an ulp of it (<= 2^-53 C: the halving is exact), and the midpoint of two points
// off the line by d_a, d_b is off by at most max(d_a, d_b) plus its own rounding, so k levels
// of bisection stay within k 2^-53 C per coordinate, sqrt(2) k 2^-53 C in distance. A
// cluster's split point (an input angle < 60 degrees) is a + s (m - a) with s a rounded
// factor: a few roundings of the same size. Here k <= log2(edge / max_edge) + 1 <= 5 and the
// distance is computed in double with an error below 2^-51 C; 16 2^-53 C covers it all.
constexpr double oblique_tolerance = 16.0 * 0x1p-53;

void check_input_nodes(const Polygon& polygon, const rk::TriangleMesh& mesh) {
  BOOST_TEST_REQUIRE(mesh.nodes.size() >= polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    BOOST_TEST_INFO("vertex " << i);
    BOOST_TEST(std::bit_cast<std::uint64_t>(mesh.nodes[i].x) == std::bit_cast<std::uint64_t>(polygon[i].x));
    BOOST_TEST(std::bit_cast<std::uint64_t>(mesh.nodes[i].y) == std::bit_cast<std::uint64_t>(polygon[i].y));
  }
}

// Orientation, indices, area sum, size and shape bounds.
void check_triangles(const rk::TriangleMesh& mesh, double max_edge, double area, Measured& measured) {
  const std::vector<Point2>& p = mesh.nodes;
  std::vector<bool> used(p.size(), false);
  double area_sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    BOOST_TEST_INFO("triangle " << t);
    BOOST_TEST_REQUIRE((tri[0] < p.size() && tri[1] < p.size() && tri[2] < p.size()));
    for (Index k : tri) used[k] = true;
    const Point2 a = p[tri[0]], b = p[tri[1]], c = p[tri[2]];
    BOOST_TEST((rk::orientation<rk::Filtered>(a, b, c) == rk::Sign::positive));
    area_sum += 0.5 * cross(a, b, c);
    const Point2 v[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Point2 o = v[k], q = v[(k + 1) % 3], r = v[(k + 2) % 3];
      const double dx = q.x - o.x, dy = q.y - o.y;
      const double ratio_sq = (dx * dx + dy * dy) / (max_edge * max_edge);  // CGAL's expression
      BOOST_TEST(ratio_sq <= 1.0);
      measured.max_edge_ratio = std::max(measured.max_edge_ratio, std::sqrt(ratio_sq));
      const double angle = std::atan2(std::abs(cross(o, q, r)), dot(o, q, r)) * 180.0 / pi;
      measured.min_angle_deg = std::min(measured.min_angle_deg, angle);
    }
  }
  BOOST_TEST(measured.min_angle_deg >= 20.0);
  BOOST_TEST(std::count(used.begin(), used.end(), false) == 0);
  // Each triangle's area carries a relative rounding of a few 2^-53, the sum adds one per
  // term: with < 10^4 triangles the error is below 1e-11 of the area; 1e-12 absolute holds
  // for the unit-sized cases here.
  BOOST_TEST(std::abs(area_sum - area) <= 1e-12 * std::max(1.0, area));
  measured.triangles = mesh.triangles.size();
}

// Conformity: the edges used once are exactly the boundary loop's, in its direction.
void check_conformity(const rk::TriangleMesh& mesh) {
  std::set<std::pair<Index, Index>> directed;
  for (const auto& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const bool fresh = directed.insert({tri[k], tri[(k + 1) % 3]}).second;
      BOOST_TEST(fresh, "directed edge " << tri[k] << "->" << tri[(k + 1) % 3] << " used twice");
    }
  }
  std::set<std::pair<Index, Index>> once;
  for (const auto& [a, b] : directed) {
    if (!directed.contains({b, a})) once.insert({a, b});
  }
  std::set<std::pair<Index, Index>> loop_edges;
  const std::size_t m = mesh.boundary.size();
  for (std::size_t i = 0; i < m; ++i) loop_edges.insert({mesh.boundary[i], mesh.boundary[(i + 1) % m]});
  BOOST_TEST(loop_edges.size() == m);
  BOOST_TEST((once == loop_edges));
}

// The loop passes the vertices in order, with the Steiner points of edge i between vertex i
// and i + 1, on the edge, in order along it.
void check_boundary(const Polygon& polygon, const rk::TriangleMesh& mesh, Measured& measured) {
  const std::size_t n = polygon.size();
  BOOST_TEST_REQUIRE(!mesh.boundary.empty());
  BOOST_TEST(mesh.boundary.front() == 0u);
  double scale = 0.0;
  for (const Point2& v : polygon) scale = std::max({scale, std::abs(v.x), std::abs(v.y)});
  std::size_t pos = 0;
  for (std::size_t i = 0; i < n; ++i) {
    BOOST_TEST_INFO("polygon edge " << i);
    BOOST_TEST_REQUIRE(pos < mesh.boundary.size());
    BOOST_TEST_REQUIRE(mesh.boundary[pos] == i);
    const Point2 a = polygon[i], b = polygon[(i + 1) % n];
    const double length_sq = dot(a, b, b);
    const bool axis_parallel = a.x == b.x || a.y == b.y;
    double last_t = 0.0;
    for (++pos; pos < mesh.boundary.size() && mesh.boundary[pos] >= n; ++pos) {
      const Point2 s = mesh.nodes[mesh.boundary[pos]];
      const double t = dot(a, b, s);
      BOOST_TEST((last_t < t && t < length_sq));
      last_t = t;
      if (axis_parallel) {
        BOOST_TEST((rk::orientation<rk::Filtered>(a, b, s) == rk::Sign::zero));
      } else {
        const double off = std::abs(cross(a, b, s)) / std::sqrt(length_sq);
        BOOST_TEST(off <= oblique_tolerance * scale);
        measured.max_off_line = std::max(measured.max_off_line, off);
      }
    }
    const std::size_t expected_next = (i + 1) % n;
    if (expected_next == 0) BOOST_TEST(pos == mesh.boundary.size());
  }
}

// Runs every check; `area` is the polygon's analytic area.
Measured check_mesh(const std::string& name, const Polygon& polygon, double max_edge, double area) {
  const rk::TriangleMesh mesh = rk::mesh_polygon(polygon, max_edge);
  BOOST_TEST_CONTEXT("case " << name) {
    Measured measured;
    check_input_nodes(polygon, mesh);
    check_triangles(mesh, max_edge, area, measured);
    check_conformity(mesh);
    check_boundary(polygon, mesh, measured);
    BOOST_TEST_MESSAGE(name << ": " << mesh.nodes.size() << " nodes, " << measured.triangles << " triangles, "
                            << mesh.boundary.size() << " boundary nodes, smallest angle " << measured.min_angle_deg
                            << " deg, longest edge " << measured.max_edge_ratio << " max_edge, oblique "
                            << "boundary points off their line by <= " << measured.max_off_line << " m");
    return measured;
  }
  return {};
}

// The hard lower bound of the element count (see the cases).
double equilateral_count(double area, double max_edge) {
  return area / (max_edge * max_edge * std::sqrt(3.0) / 4.0);
}

void check_count(const Measured& measured, double area, double max_edge) {
  const double lower = equilateral_count(area, max_edge);
  const double count = static_cast<double>(measured.triangles);
  BOOST_TEST_MESSAGE("  count / (area / (max_edge² √3/4)) = " << count / lower);
  BOOST_TEST(count >= lower);
  // Refinement stops as soon as every triangle meets both bounds, so away from the corners
  // elements are not much smaller than max_edge: observed ratios 2.07-2.17; 4 leaves margin.
  BOOST_TEST(count <= 4.0 * lower);
}

// Asserts that `call` throws std::invalid_argument whose message contains every needle.
void expect_invalid(const std::string& name, const std::function<void()>& call,
                    const std::vector<std::string>& needles) {
  BOOST_TEST_INFO("case " << name);
  try {
    call();
    BOOST_TEST(false, "no std::invalid_argument thrown");
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    BOOST_TEST_MESSAGE(name << ": " << message);
    for (const std::string& needle : needles) {
      BOOST_TEST_INFO("case " << name << ", message: " << message);
      BOOST_TEST(message.find(needle) != std::string::npos);
    }
  }
}

const Polygon square_1x1{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const Polygon prism_triangle{{0, 0}, {1, 0}, {0.5, 0.8}};
// The L: [0,2]² without [1,2]x[1,2], area 3; the corner (1,1) is reflex (270 degrees).
const Polygon l_polygon{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

}  // namespace

// 1. The unit square with max_edge 0.1: every check, area exactly 1 up to the summation.
BOOST_AUTO_TEST_CASE(unit_square_max_edge_0_1) {
  const Measured measured = check_mesh("square", square_1x1, 0.1, 1.0);
  check_count(measured, 1.0, 0.1);
}

// 2a. The prism cross-section: a triangle of area 0.4 with base corners of atan(1.6) = 58.0
// degrees, below 60, so CGAL forms clusters there; two oblique edges.
BOOST_AUTO_TEST_CASE(prism_cross_section) {
  const Measured measured = check_mesh("prism section", prism_triangle, 0.1, 0.4);
  check_count(measured, 0.4, 0.1);
}

// 2b. The non-convex L: only triangles inside it (none in the notch), area 3.
BOOST_AUTO_TEST_CASE(l_shape_non_convex) {
  const Measured measured = check_mesh("L", l_polygon, 0.15, 3.0);
  check_count(measured, 3.0, 0.15);
}

// 3. Bad input, one case per check; each message names what is wrong.
BOOST_AUTO_TEST_CASE(bad_input) {
  const auto mesh = [](Polygon polygon, double max_edge) {
    return [polygon, max_edge] { static_cast<void>(rk::mesh_polygon(polygon, max_edge)); };
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Polygon clockwise(square_1x1.rbegin(), square_1x1.rend());
  expect_invalid("clockwise", mesh(clockwise, 0.1), {"polygon", "clockwise", "counter-clockwise"});
  expect_invalid("repeated vertex", mesh({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}, 0.1),
                 {"polygon vertex 5 repeats vertex 2"});
  expect_invalid("repeated neighbour", mesh({{0, 0}, {1, 0}, {1, 0}, {0, 1}}, 0.1),
                 {"polygon vertex 2 repeats vertex 1"});
  expect_invalid("bow-tie", mesh({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0.1),
                 {"polygon edge 0 (vertex 0 to 1)", "polygon edge 2 (vertex 2 to 3)", "intersect", "simple"});
  expect_invalid("vertex on an edge", mesh({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}, 0.1),
                 {"polygon edge", "intersect", "simple"});
  expect_invalid("fold back", mesh({{0, 0}, {2, 0}, {1, 0}, {1, 1}}, 0.1),
                 {"polygon vertex 1", "folds back", "simple"});
  expect_invalid("collinear", mesh({{0, 0}, {1, 0}, {2, 0}}, 0.1), {"polygon", "simple"});
  expect_invalid("two vertices", mesh({{0, 0}, {1, 0}}, 0.1), {"at least 3 vertices", "got 2"});
  expect_invalid("no vertices", mesh({}, 0.1), {"at least 3 vertices", "got 0"});
  expect_invalid("NaN coordinate", mesh({{0, 0}, {nan, 0}, {0, 1}}, 0.1),
                 {"polygon vertex 1", "finite", "nan"});
  expect_invalid("infinite coordinate", mesh({{0, 0}, {1, 0}, {0, inf}}, 0.1),
                 {"polygon vertex 2", "finite", "inf"});
  expect_invalid("huge coordinate", mesh({{0, 0}, {1e60, 0}, {0, 1}}, 1.0), {"polygon vertex 1", "1e+50"});
  expect_invalid("max_edge 0", mesh(square_1x1, 0.0), {"max_edge", "finite value > 0", "got 0"});
  expect_invalid("max_edge negative", mesh(square_1x1, -0.1), {"max_edge", "got -0.1"});
  expect_invalid("max_edge NaN", mesh(square_1x1, nan), {"max_edge", "got nan"});
  expect_invalid("max_edge inf", mesh(square_1x1, inf), {"max_edge", "got inf"});
  // The estimate is 2 / (1e-4² √3/4) = 4.6e8 elements, above 5e6.
  expect_invalid("too fine", mesh(square_1x1, 1e-4), {"max_edge", "1e-04", "~4.6e+08 elements", "5000000"});
  // At 1e12 m doubles are 2^-13 m apart; 2^-30 of 1e12 is 931 m: 1 m elements are not resolved.
  const double o = 1e12, w = 1e4;
  const Polygon far{{o, o}, {o + w, o}, {o + w, o + w}, {o, o + w}};
  expect_invalid("below the resolution", mesh(far, 1.0), {"max_edge", "below 9.3e+02", "resolution"});
  // Edge 2 is 1 m long, below the 931 m resolution (max_edge 5e3 m is above it).
  const Polygon short_edge{{o, o}, {o + w, o}, {o + w, o + w}, {o + w - 1, o + w}};
  expect_invalid("short edge", mesh(short_edge, 5e3),
                 {"polygon edge 2 (vertex 2 to 3)", "length 1 m", "resolution"});
}

// 4a. The unit square moved to (1e6, 1e6): the same checks (coordinates and midpoints of the
// axis-parallel edges are exact at 1e6, doubles there are 2^-33 m apart); circumcentres round
// differently, so the mesh need not be the same as at the origin.
BOOST_AUTO_TEST_CASE(far_from_origin) {
  const double o = 1e6;
  const Polygon square{{o, o}, {o + 1, o}, {o + 1, o + 1}, {o, o + 1}};
  const Measured measured = check_mesh("square at 1e6", square, 0.1, 1.0);
  check_count(measured, 1.0, 0.1);
}

// 4b. A vertex in the middle of a straight edge (180 degrees) is kept as a node of the loop.
BOOST_AUTO_TEST_CASE(collinear_vertex) {
  const Polygon square{{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Measured measured = check_mesh("square with a collinear vertex", square, 0.1, 1.0);
  check_count(measured, 1.0, 0.1);
}

// 4c. A coarse max_edge (larger than the polygon): only the shape bound refines.
BOOST_AUTO_TEST_CASE(coarse_max_edge) {
  const Measured square = check_mesh("square, max_edge 10", square_1x1, 10.0, 1.0);
  BOOST_TEST(square.triangles == 2u);  // the two Delaunay triangles: 45-degree angles pass
  static_cast<void>(check_mesh("prism section, max_edge 10", prism_triangle, 10.0, 0.4));
}

// 4d. The same input gives the same mesh, bit for bit.
BOOST_AUTO_TEST_CASE(deterministic) {
  const rk::TriangleMesh a = rk::mesh_polygon(l_polygon, 0.15);
  const rk::TriangleMesh b = rk::mesh_polygon(l_polygon, 0.15);
  BOOST_TEST((a.nodes == b.nodes));
  BOOST_TEST((a.triangles == b.triangles));
  BOOST_TEST((a.boundary == b.boundary));
}
