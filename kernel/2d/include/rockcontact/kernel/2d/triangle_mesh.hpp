#pragma once
// Triangle meshes of a block: a simple polygon cut into constant-strain triangles for the CDEM
// engine (seed 003), by Delaunay refinement (Ruppert, "A Delaunay refinement algorithm for
// quality 2-dimensional mesh generation", J. Algorithms 18, 1995; Shewchuk, "Delaunay refinement
// algorithms for triangular mesh generation", CGTA 22, 2002), as implemented by CGAL's
// Delaunay_mesher_2 (package "2D Conforming Triangulations and Meshes").
//
// mesh_polygon, step by step:
//   1. Validate (each std::invalid_argument message names the vertex, the edge or max_edge and
//      what was expected; the caller prefixes the block id): >= 3 vertices, finite coordinates
//      within +-mesh_max_coordinate, no repeated vertex, a simple polygon (no two edges meet
//      except adjacent ones at their common vertex) and counter-clockwise, decided by exact
//      predicates (CGAL's is_simple_2 and orientation_2 on the exact-predicates kernel). Then
//      max_edge and every edge must be at least the resolution (below), and the work is
//      bounded: the mesh must not need more than max_mesh_triangles elements, estimated as
//      2 area / (max_edge² √3/4). area / (max_edge² √3/4), the number of equilateral triangles
//      of side max_edge that tile the area, is a lower bound of the count (no triangle with
//      edges <= max_edge has more area); Delaunay refinement under a longest-edge bound gives
//      about twice it (2.07 to 2.17 on the shapes of tests/triangle_mesh_test.cpp), as its
//      typical edge is about 0.7 max_edge.
//   2. Insert the vertices and the polygon's edges as constraints into a constrained Delaunay
//      triangulation (exact predicates, constructions in double). The faces enclosed by the
//      constraints are the domain (the mesher's seeds-free marking: every face not reachable
//      from the infinite face without crossing a constraint).
//   3. Refine with Delaunay_mesh_size_criteria_2(B = 0.125, max_edge) until no triangle of the
//      domain is bad:
//        - size: its longest edge exceeds max_edge (CGAL compares the squared length with
//          max_edge², in double);
//        - shape: sin² of its smallest angle is below B. B = 0.125 is CGAL's default and means a
//          smallest angle of asin(sqrt(1/8)) = 20.70 degrees, i.e. a circumradius-to-shortest-edge
//          ratio of sqrt(2): the largest angle bound for which Delaunay refinement is proven to
//          terminate (Shewchuk 2002, for inputs without angles below 60 degrees). Larger bounds
//          (~30 degrees) usually work but are not proven to terminate; the CST stiffness and the
//          stable time step only need the angles kept away from 0 and 180 degrees, and 20.7
//          degrees also bounds the largest angle, by 180 - 2 x 20.7 = 138.6.
//      Boundary edges are refined too (Delaunay_mesher_2, not the no-edge-refinement variant):
//      a constrained edge encroached by a vertex or by a bad triangle's circumcentre is split
//      at its midpoint (near an input angle below 60 degrees, at a point on a circle around
//      the corner: CGAL's clusters), so the boundary gets Steiner points and every boundary
//      edge is an edge of a triangle that meets both bounds. Refinement runs one point at a
//      time and stops with std::invalid_argument once the triangulation passes
//      3/4 max_mesh_triangles vertices, about 1.5 times the element limit: parts of the polygon
//      far narrower than max_edge (a thin strip, a vertex close to another edge) force far
//      more elements than the area predicts.
//   4. Output (see TriangleMesh): nodes numbered input vertices first; the Steiner points
//      sorted by their lowest, then leftmost position, so numbering depends only on the
//      geometry; triangles rotated to start at their smallest node index and sorted; the
//      boundary walked counter-clockwise from node 0. Every triangle is checked to be strictly
//      counter-clockwise (exact orientation on the output doubles).
//
// Guarantees: the input vertices are nodes 0..n-1 with their exact coordinates; every triangle
// is strictly counter-clockwise; the triangles are conforming (an interior edge is shared by
// exactly two triangles, a boundary edge belongs to one) and cover the polygon; the boundary
// loop's edges are exactly the edges used by one triangle. Every triangle edge satisfies
// length² / max_edge² <= 1 as CGAL evaluates it in double (so in real numbers length <=
// max_edge (1 + ~2^-52)); every angle is >= 20.7 degrees except possibly near a vertex where
// two polygon edges meet at less than 60 degrees, on either side (a sharp corner, or the tip of
// a sharp notch): Delaunay refinement cannot reach the bound there, and CGAL (its "clusters")
// leaves such triangles rather than refine forever, so their angles may fall below the bound
// and even below the corner's own angle.
// Where it is not exact: Steiner points are CGAL's double constructions. On an axis-parallel
// edge (and on any edge whose midpoints are representable) they lie exactly on the edge; on an
// oblique edge each is within a few half-ulps of its coordinates of the edge's line, so the
// boundary is the polygon up to that rounding (the area covered differs from the polygon's by
// about the perimeter times that distance).
//
// The resolution, max(mesh_resolution_factor * largest |coordinate|, mesh_min_length): double
// coordinates near c are spaced <= 2^-52 |c| apart, so an element edge of at least 2^-30 |c|
// spans >= 2^22 of those spacings and CGAL's midpoints and circumcentres, rounded to that
// spacing, stay well inside the quality bounds' slack. Far below it, midpoints round onto their
// end points, which the mesher does not handle. The absolute bounds keep CGAL's shape test in
// range for elements of at least mesh_min_length: it divides area² by products of squared
// lengths (length⁴), which overflow double above about 1e77 m and underflow below 1e-77 m.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

// Work bound of mesh_polygon: at most this many elements estimated from the area (step 1),
// at most 3/4 this many vertices during refinement (step 3).
inline constexpr std::size_t max_mesh_triangles = 5'000'000;

// Resolution of mesh_polygon (see the header comment): max_edge and every polygon edge must be
// at least max(mesh_resolution_factor * largest |coordinate|, mesh_min_length) metres, and
// every coordinate within +-mesh_max_coordinate metres.
inline constexpr double mesh_resolution_factor = 0x1p-30;
inline constexpr double mesh_min_length = 1e-50;      // m
inline constexpr double mesh_max_coordinate = 1e50;   // m

struct TriangleMesh {
  // m. The polygon's vertices first, in the given order and with their exact coordinates,
  // then the Steiner points (on the boundary and inside), lowest then leftmost first.
  std::vector<Point2> nodes;
  // Node indices of each triangle, counter-clockwise (positive area), smallest index first;
  // sorted lexicographically.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // The boundary as a closed loop of node indices, counter-clockwise (interior on the left),
  // starting at node 0: consecutive entries, and the last with the first, are the boundary
  // edges. It passes the polygon's vertices 0, 1, ..., n-1 in order, with the Steiner points of
  // each subdivided polygon edge between its end points, in order along the edge.
  std::vector<std::uint32_t> boundary;
};

// Meshes a simple counter-clockwise polygon (m) into triangles whose longest edge is at most
// max_edge (m, finite > 0) and whose smallest angle is at least 20.7 degrees (see above),
// refining the boundary too. Throws std::invalid_argument for bad input (messages name the
// vertex index, edge or max_edge, and what was expected) and when the mesh would exceed
// max_mesh_triangles; std::runtime_error if CGAL's output breaks a guarantee above (a rounded
// Steiner point making a triangle degenerate), which the checks in step 4 catch.
TriangleMesh mesh_polygon(std::span<const Point2> polygon, double max_edge);

}  // namespace rockcontact::kernel
