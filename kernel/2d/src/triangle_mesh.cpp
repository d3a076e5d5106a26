#include "rockcontact/kernel/2d/triangle_mesh.hpp"

// CGAL's 2D mesher is confined to this file (with block_cutting.cpp, the slow kernel sources to
// compile); see the header for the method.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include "rockcontact/kernel/2d/block_cutting.hpp"

namespace rockcontact::kernel {

namespace {

// Exact predicates, double constructions: every input double is a CGAL point as it is, and
// the Steiner points CGAL constructs are doubles too, so nothing is rounded on output.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = K::Point_2;

// A vertex's node index; Steiner points start unnumbered (a default member initialiser, since
// the info of a vertex CGAL creates is default-constructed).
constexpr std::uint32_t unnumbered = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t discovered = unnumbered - 1;
struct NodeIndex {
  std::uint32_t value = unnumbered;
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<NodeIndex, K, CGAL::Delaunay_mesh_vertex_base_2<K>>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// The validated polygon's edges meet only at shared end points: CGAL may reject any crossing.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;
using Vertex = Cdt::Vertex_handle;
using Face = Cdt::Face_handle;

// sin² of the smallest angle a good triangle has: CGAL's default (see the header).
constexpr double shape_bound = 0.125;

// ---------------------------------------------------------------------------------------------
// Messages

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument(message); }

// Shortest decimal form that reads back as the same double ("-1", "0.1", "nan").
std::string num(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// Two significant digits, for estimates ("1.2e+08").
std::string approx(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 2).ptr;
  return std::string(buffer, end);
}

std::string vertex(std::size_t i) { return "polygon vertex " + std::to_string(i); }

std::string edge(std::size_t i, std::size_t n) {
  return "polygon edge " + std::to_string(i) + " (vertex " + std::to_string(i) + " to " +
         std::to_string((i + 1) % n) + ")";
}

// ---------------------------------------------------------------------------------------------
// Validation (step 1)

void validate_max_edge(double max_edge) {
  if (!(std::isfinite(max_edge) && max_edge > 0.0)) {
    fail("max_edge: expected a finite value > 0 (m), got " + num(max_edge));
  }
}

void validate_vertices(std::span<const Point2> polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) fail("polygon: needs at least 3 vertices, got " + std::to_string(n));
  // A triangulation of n vertices has at least n - 2 triangles.
  if (n - 2 > max_mesh_triangles) {
    fail("polygon: " + std::to_string(n) + " vertices give more than " + std::to_string(max_mesh_triangles) +
         " triangles");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 p = polygon[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      fail(vertex(i) + ": coordinates must be finite, got (" + num(p.x) + ", " + num(p.y) + ")");
    }
    if (std::abs(p.x) > mesh_max_coordinate || std::abs(p.y) > mesh_max_coordinate) {
      fail(vertex(i) + ": coordinates must lie within +-" + num(mesh_max_coordinate) + " m, got (" + num(p.x) +
           ", " + num(p.y) + ")");
    }
  }
  // Repeated vertices: sorted by position, equal points are neighbours (O(n log n)).
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  const auto key = [&](std::size_t i) { return std::tuple(polygon[i].x, polygon[i].y, i); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  for (std::size_t k = 1; k < n; ++k) {
    if (polygon[order[k]] == polygon[order[k - 1]]) {
      fail(vertex(order[k]) + " repeats vertex " + std::to_string(order[k - 1]) + " at (" +
           num(polygon[order[k]].x) + ", " + num(polygon[order[k]].y) + ")");
    }
  }
}

// The first defect that makes a polygon without repeated vertices non-simple, for the message
// (only called on failure: O(n²)). Exact: CGAL's predicates on the exact-predicates kernel.
std::string why_not_simple(const std::vector<CgalPoint>& v) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const CgalPoint& prev = v[(i + n - 1) % n];
    const CgalPoint& next = v[(i + 1) % n];
    if (CGAL::collinear(prev, v[i], next) &&
        !CGAL::collinear_are_strictly_ordered_along_line(prev, v[i], next)) {
      return vertex(i) + ": the boundary folds back on itself";
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (CGAL::do_intersect(K::Segment_2(v[i], v[i + 1]), K::Segment_2(v[j], v[(j + 1) % n]))) {
        return edge(i, n) + " and " + edge(j, n) + " intersect";
      }
    }
  }
  return "polygon: the boundary intersects itself";
}

std::vector<CgalPoint> validate_shape(std::span<const Point2> polygon) {
  std::vector<CgalPoint> points;
  points.reserve(polygon.size());
  for (const Point2& p : polygon) points.emplace_back(p.x, p.y);
  if (!CGAL::is_simple_2(points.begin(), points.end(), K())) {
    fail(why_not_simple(points) + " (a simple polygon is required)");
  }
  const CGAL::Orientation orientation = CGAL::orientation_2(points.begin(), points.end(), K());
  if (orientation == CGAL::CLOCKWISE) {
    fail("polygon: vertices are clockwise; counter-clockwise order (interior on the left) is required");
  }
  if (orientation != CGAL::COUNTERCLOCKWISE) fail("polygon: the polygon has zero area");
  return points;
}

// The resolution, then the work bound (see the header). The resolution comes first: it bounds
// max_edge from below, so the predicted count is finite when it is reported.
void validate_size(std::span<const Point2> polygon, double max_edge) {
  double largest = 0.0;
  for (const Point2& p : polygon) largest = std::max({largest, std::abs(p.x), std::abs(p.y)});
  const double resolution = std::max(mesh_resolution_factor * largest, mesh_min_length);
  const std::string why = " m, the resolution of double coordinates as large as " + approx(largest) +
                          " m (2^-30 of them, at least " + num(mesh_min_length) + " m)";
  if (max_edge < resolution) {
    fail("max_edge: " + num(max_edge) + " m is below " + approx(resolution) + why +
         "; use a larger max_edge or move the polygon nearer the origin");
  }
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = polygon[i], b = polygon[(i + 1) % n];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    if (length < resolution) {
      fail(edge(i, n) + ": its length " + num(length) + " m is below " + approx(resolution) + why);
    }
  }
  // Twice the equilateral count (see the header).
  const double area = polygon_area(polygon);
  const double predicted = 2.0 * (area / max_edge / max_edge / (std::numbers::sqrt3 / 4.0));
  if (!(predicted <= static_cast<double>(max_mesh_triangles))) {
    fail("max_edge: " + num(max_edge) + " m would give a mesh of ~" + approx(predicted) +
         " elements on this polygon of area " + approx(area) + " m² (at most " +
         std::to_string(max_mesh_triangles) + "); use a larger max_edge");
  }
}

// ---------------------------------------------------------------------------------------------
// Meshing (steps 2, 3)

void insert_polygon(Cdt& cdt, const std::vector<CgalPoint>& points) {
  std::vector<Vertex> vertices;
  vertices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    vertices.push_back(cdt.insert(points[i]));
    vertices.back()->info().value = static_cast<std::uint32_t>(i);
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    cdt.insert_constraint(vertices[i], vertices[(i + 1) % vertices.size()]);
  }
}

// Mesher::refine_mesh() inserts every point in one call; stepping one point at a time inserts
// the same points in the same order (edges before faces, CGAL's Mesher_level) and lets the
// work bound stop a mesh that small features blow up. A mesh has about twice as many triangles
// as vertices, so the bound, 3/4 max_mesh_triangles vertices, is about 1.5 times the element
// limit: only a mesh far above its estimate reaches it.
void refine(Cdt& cdt, double max_edge) {
  Mesher mesher(cdt, Criteria(shape_bound, max_edge));
  mesher.init();  // seeds-free: the domain is what the constraints enclose
  const std::size_t max_vertices = max_mesh_triangles / 4 * 3;
  while (mesher.step_by_step_refine_mesh()) {
    if (cdt.number_of_vertices() > max_vertices) {
      fail("polygon: the mesh passed " + std::to_string(max_vertices) + " nodes (about " +
           approx(2.0 * static_cast<double>(max_vertices)) + " elements, at most " +
           std::to_string(max_mesh_triangles) + ") before meeting max_edge " + num(max_edge) +
           " m and the 20.7 degree angle bound: parts of the polygon far narrower than max_edge (thin "
           "strips, vertices close to other edges, short edges, sharp corners) force smaller elements");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Output (step 4)

[[noreturn]] void broken(const std::string& what) {
  throw std::runtime_error("mesh_polygon: CGAL's mesh breaks a guarantee: " + what);
}

bool below_or_left(const Point2& a, const Point2& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }

Point2 to_point(const CgalPoint& p) { return {p.x(), p.y()}; }

// Numbers the Steiner points of the domain's faces after the input vertices, lowest then
// leftmost first, and returns the nodes. Vertices outside the domain (none are expected) get
// no number and appear in no triangle.
std::vector<Point2> number_nodes(Cdt& cdt, std::span<const Point2> polygon) {
  std::vector<Vertex> steiner;
  for (const Face face : cdt.finite_face_handles()) {
    if (!face->is_in_domain()) continue;
    for (int k = 0; k < 3; ++k) {
      const Vertex v = face->vertex(k);
      if (v->info().value != unnumbered) continue;
      v->info().value = discovered;
      steiner.push_back(v);
    }
  }
  std::sort(steiner.begin(), steiner.end(),
            [](Vertex a, Vertex b) { return below_or_left(to_point(a->point()), to_point(b->point())); });
  std::vector<Point2> nodes(polygon.begin(), polygon.end());
  for (const Vertex v : steiner) {
    v->info().value = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(to_point(v->point()));
  }
  return nodes;
}

std::vector<std::array<std::uint32_t, 3>> collect_triangles(const Cdt& cdt) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const Face face : cdt.finite_face_handles()) {
    if (!face->is_in_domain()) continue;
    const CgalPoint &a = face->vertex(0)->point(), &b = face->vertex(1)->point(), &c = face->vertex(2)->point();
    // CGAL's faces are counter-clockwise by construction, but a boundary Steiner point is
    // inserted on its edge by its combinatorics, whatever its rounding: check exactly.
    if (CGAL::orientation(a, b, c) != CGAL::LEFT_TURN) {
      broken("the triangle at (" + num(a.x()) + ", " + num(a.y()) + "), (" + num(b.x()) + ", " + num(b.y()) +
             "), (" + num(c.x()) + ", " + num(c.y()) + ") is not strictly counter-clockwise");
    }
    std::array<std::uint32_t, 3> t{face->vertex(0)->info().value, face->vertex(1)->info().value,
                                   face->vertex(2)->info().value};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keeps the orientation
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// The boundary edges are the domain faces' edges whose other side is outside the domain; in a
// counter-clockwise face, the edge opposite vertex i runs from vertex ccw(i) to vertex cw(i)
// with the face on its left. On a simple polygon every boundary node has one outgoing edge.
std::vector<std::uint32_t> walk_boundary(const Cdt& cdt, std::size_t node_count) {
  std::vector<std::uint32_t> next(node_count, unnumbered);
  std::size_t edges = 0;
  for (const Face face : cdt.finite_face_handles()) {
    if (!face->is_in_domain()) continue;
    for (int i = 0; i < 3; ++i) {
      if (face->neighbor(i)->is_in_domain()) continue;
      const std::uint32_t from = face->vertex(Cdt::ccw(i))->info().value;
      if (next[from] != unnumbered) broken("node " + std::to_string(from) + " has two boundary edges");
      next[from] = face->vertex(Cdt::cw(i))->info().value;
      ++edges;
    }
  }
  std::vector<std::uint32_t> loop;
  for (std::uint32_t node = 0; loop.size() < edges; node = next[node]) {
    loop.push_back(node);
    if (next[node] == unnumbered) broken("the boundary stops at node " + std::to_string(node));
    if (next[node] == 0) break;
  }
  if (loop.size() != edges) broken("the boundary is not one loop through node 0");
  return loop;
}

}  // namespace

TriangleMesh mesh_polygon(std::span<const Point2> polygon, double max_edge) {
  validate_max_edge(max_edge);
  validate_vertices(polygon);
  const std::vector<CgalPoint> points = validate_shape(polygon);
  validate_size(polygon, max_edge);
  Cdt cdt;
  insert_polygon(cdt, points);
  refine(cdt, max_edge);
  TriangleMesh mesh;
  mesh.nodes = number_nodes(cdt, polygon);
  mesh.triangles = collect_triangles(cdt);
  mesh.boundary = walk_boundary(cdt, mesh.nodes.size());
  return mesh;
}

}  // namespace rockcontact::kernel
