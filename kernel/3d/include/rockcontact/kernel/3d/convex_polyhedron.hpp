#pragma once
// ConvexPolyhedron: a validated convex polyhedron, the 3D block of the kernel.
//
// Given as vertices (doubles, exact as given) and faces (loops of vertex indices,
// counter-clockwise seen from outside), it is the convex hull of its vertices, and make()
// proves it with exact predicates (orient3d under the staged engine), so every later decision
// may rely on it:
//   * at least 4 vertices, all finite and distinct;
//   * every face has at least 3 distinct, valid vertex indices, and every vertex is on a face;
//   * the faces close a consistently oriented 2-manifold: every directed edge a -> b of a face
//     is traversed once, and b -> a once by another face;
//   * every face is planar: exactly, or to within face_planarity_tolerance of the block's size
//     (tolerances.hpp) when its vertices come from a rotation, a strain or rounding;
//   * the facets (below) are strictly convex, and every vertex not on a facet lies strictly
//     below its plane (inside); so coplanar neighbouring faces must be merged into one face, and
//     a vertex in the middle of an edge or a face is an error.
// A violation throws InvalidPolyhedron naming the block, the face (as given) and the vertex.
//
// Faces and facets. A face planar only to rounding is not one plane of the solid: the exact hull
// of the vertices bends along one or more diagonals of it. make() splits such a face into the
// facets of the exact hull that it covers (the outward hull of its own vertices, decided by
// orient3d, coplanar triangles merged), so every facet is exactly planar and every query may take
// a facet's first three vertices as its plane. faces() lists the facets; input_face(i) names the
// face each came from; a face that is exactly planar is one facet, so for such blocks the two
// lists are the same. edges() lists the hull's edges, the diagonals of split faces included.
//
// Feature ids. The contact history of the 3D DDA (seed 001 §4.2) follows a contact by the
// features it joins, so these must not be re-derived from rounded geometry each step: a vertex
// is its index, an edge its two vertex indices (edges()[i] is a pair, so an index into edges()
// is stable only while the split of bent faces is), a face its index as given (input_face()
// maps a facet to it). All come from the input: moved() re-validates new coordinates against
// the same faces and keeps them, and only the split of a bent face into facets (a facet's index,
// a diagonal) may change with rounding. The kernel's queries report facets and edge indices
// (contact_constraints.hpp); a caller that keeps history across steps maps them through
// input_face() and edges().

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/3d/tolerances.hpp"

namespace rockcontact::kernel {

class InvalidPolyhedron : public std::invalid_argument {
 public:
  enum class Reason {
    too_few_vertices,
    non_finite,
    repeated_vertex,
    bad_face,       // fewer than 3 vertices, an index out of range or repeated
    unused_vertex,  // on no face
    not_closed,     // a directed edge not matched by its reverse exactly once
    not_planar,     // a face vertex off the face's plane by more than the tolerance
    not_convex      // a face not strictly convex, or a vertex on or above another face's plane
  };

  // face or vertex < 0 when the problem is not about one.
  InvalidPolyhedron(std::string block, std::ptrdiff_t face, std::ptrdiff_t vertex, Reason reason,
                    const std::string& what);

  const std::string& block() const noexcept { return block_; }
  std::ptrdiff_t face() const noexcept { return face_; }
  std::ptrdiff_t vertex() const noexcept { return vertex_; }
  Reason reason() const noexcept { return reason_; }

 private:
  std::string block_;
  std::ptrdiff_t face_;
  std::ptrdiff_t vertex_;
  Reason reason_;
};

class ConvexPolyhedron {
 public:
  using Face = std::vector<std::uint32_t>;
  // An edge as its two vertex indices, first < second.
  using Edge = std::pair<std::uint32_t, std::uint32_t>;

  // Validates as the header states; throws InvalidPolyhedron naming `name`.
  static ConvexPolyhedron make(std::string name, std::vector<Point3> vertices, std::vector<Face> faces);

  // The same block with new vertex coordinates (moved, rotated, deformed), validated against the
  // same faces; vertex indices and faces as given keep their ids.
  ConvexPolyhedron moved(std::vector<Point3> vertices) const;

  // The same block under another name (the name errors and messages give).
  ConvexPolyhedron renamed(std::string name) const {
    ConvexPolyhedron out = *this;
    out.name_ = std::move(name);
    return out;
  }

  const std::string& name() const noexcept { return name_; }
  std::span<const Point3> vertices() const noexcept { return vertices_; }
  // The exactly planar facets, counter-clockwise seen from outside.
  std::span<const Face> faces() const noexcept { return facets_; }
  // The index, in input_faces(), of the face facet `facet` lies in.
  std::size_t input_face(std::size_t facet) const { return input_face_[facet]; }
  // The faces as given to make().
  std::span<const Face> input_faces() const noexcept { return input_faces_; }
  std::span<const Edge> edges() const noexcept { return edges_; }
  // Per edge (first, second): the facet whose loop runs first -> second, then the one whose loop
  // runs second -> first. For outward normals n1, n2 of these facets, n1 x n2 points along
  // second - first.
  std::span<const std::array<std::uint32_t, 2>> edge_faces() const noexcept { return edge_faces_; }
  const Point3& operator[](std::size_t i) const { return vertices_[i]; }
  std::size_t size() const noexcept { return vertices_.size(); }

 private:
  ConvexPolyhedron() = default;

  std::string name_;
  std::vector<Point3> vertices_;
  std::vector<Face> input_faces_;
  std::vector<Face> facets_;
  std::vector<std::size_t> input_face_;  // per facet
  std::vector<Edge> edges_;
  std::vector<std::array<std::uint32_t, 2>> edge_faces_;  // per edge
};

}  // namespace rockcontact::kernel
