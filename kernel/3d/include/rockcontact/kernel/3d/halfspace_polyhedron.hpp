#pragma once
// HalfspacePolyhedron: a convex polyhedron as planes and faces, with implicit vertices, the
// form clipping produces (plane_cut.hpp, intersection.hpp).
//
// A polyhedron is the intersection of the closed sides below its face planes (plane.hpp); its
// boundary is given combinatorially:
//   * planes: Plane3 values, each exact as given (through three input points, or by double
//     coefficients); a plane stays in the list after its face is cut away, since implicit
//     vertices may still refer to it;
//   * faces: the index of the face's plane and the loop of its vertex ids, counter-clockwise
//     seen from outside (the normal's side);
//   * vertices: an input point (exact as given), or the meeting point of three planes given by
//     their indices (implicit: never rounded to decide anything).
// Invariants, kept by construction: the faces close a consistently oriented 2-manifold, each
// face is a strictly convex polygon with non-zero area, and the polyhedron has an interior.
// The empty polyhedron (no faces, no vertices) is the result of a clip that leaves no interior.
//
// Constructions, after every decision:
//   vertex_coordinates<P>()  Float, Filtered, Checked: an input vertex as given; an implicit
//                            one by Cramer's rule in double, in a frame at the polyhedron's
//                            first input vertex (so the coefficients stay small for a pair far
//                            from the origin), with a running error bound
//                            (detail/running_error.hpp); a vertex not certified within 2^-42 of
//                            the polyhedron's extent (three nearly dependent planes, e.g. faces
//                            of two blocks parallel to within rounding: about 7% of the implicit
//                            vertices of the contact3d random pairs) is instead divided from its
//                            exact homogeneous coordinates (det X and det in CGAL::Mpzf, each
//                            rounded once where both are normal doubles, else their exact
//                            quotient rounded once), within 5 eps of its size. Exact: Cramer's
//                            rule in exact rationals, each coordinate rounded once.
//   volume<P>()              divergence theorem: the sum over faces of the fan triangles'
//                            signed tetrahedron volumes (1/6 det) about the first vertex, in
//                            the same local frame. Filtered, Checked: with a bound on its error
//                            from the vertices' bounds and the sum's roundings, kept when within
//                            2^-31 |V| or 2^-41 R^3 of the exact V (R: the largest frame coordinate
//                            of the vertices and of the points the planes are through, at most
//                            the size of the pair's bounding box for an intersection); else the
//                            loosely certified vertices are divided from their exact homogeneous
//                            coordinates and the bound taken again (of 2e4 volumes of the 3D
//                            generators' pairs: 5% of the rotated ones, under 1% of the others);
//                            else the exact volume (none of those). Float: the sum unchecked.
//                            Exact: the double nearest to the exact rational volume, found
//                            lazily: the same sum in DoubleDouble with a running error bound
//                            (implicit vertices by Cramer's rule, or from their exact Mpzf
//                            homogeneous coordinates where the planes are nearly dependent),
//                            accepted when the bound settles the rounding; else the exact
//                            rational volume rounded once (detail/halfspace_exact.hpp exposes
//                            both).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

class HalfspacePolyhedron {
 public:
  struct Vertex {
    bool input = true;                     // an input point, else the meeting point of `planes`
    Point3 point{};                        // input only
    std::array<std::uint32_t, 3> planes{};  // implicit only: indices into planes()
    friend bool operator==(const Vertex&, const Vertex&) = default;
  };
  struct Face {
    std::uint32_t plane = 0;           // index into planes()
    std::vector<std::uint32_t> loop;  // vertex ids, counter-clockwise from outside
    friend bool operator==(const Face&, const Face&) = default;
  };

  // The empty polyhedron.
  HalfspacePolyhedron() = default;
  // p's face planes (through each face's first three vertices) and its vertices as input points.
  explicit HalfspacePolyhedron(const ConvexPolyhedron& p);
  // From parts that satisfy the invariants above (asserted in debug builds only): for clipping.
  HalfspacePolyhedron(std::vector<Plane3> planes, std::vector<Face> faces, std::vector<Vertex> vertices);

  std::span<const Plane3> planes() const noexcept { return planes_; }
  std::span<const Face> faces() const noexcept { return faces_; }
  std::span<const Vertex> vertices() const noexcept { return vertices_; }
  bool empty() const noexcept { return faces_.empty(); }

  // The side of plane s at vertex v (plane.hpp's predicates; zero without a predicate when s is
  // one of an implicit vertex's planes).
  template <NumberPolicy Policy>
  Sign side(std::uint32_t v, const Plane3& s) const;

  // The side of plane s at every vertex: side() for each, with the three-plane side's double
  // filter evaluated on plane coefficients computed once per plane instead of once per call
  // (the same signs, the same counters, the same Checked comparison).
  template <NumberPolicy Policy>
  std::vector<Sign> sides(const Plane3& s) const;

  template <NumberPolicy Policy>
  std::vector<Point3> vertex_coordinates() const;

  // Cubic metres; 0 for the empty polyhedron.
  template <NumberPolicy Policy>
  double volume() const;

  // The origin of the local frame of the constructions: the first input vertex, else the
  // reference point of the first plane.
  Point3 frame_origin() const;

 private:
  std::vector<Plane3> planes_;
  std::vector<Face> faces_;
  std::vector<Vertex> vertices_;
};

template <NumberPolicy Policy>
Sign HalfspacePolyhedron::side(std::uint32_t v, const Plane3& s) const {
  const Vertex& vertex = vertices_[v];
  if (vertex.input) return side_of_plane<Policy>(s, vertex.point);
  const Plane3 &p = planes_[vertex.planes[0]], &q = planes_[vertex.planes[1]], &r = planes_[vertex.planes[2]];
  if (s == p || s == q || s == r) return Sign::zero;
  return side_of_plane<Policy>(s, p, q, r);
}

}  // namespace rockcontact::kernel
