#pragma once
// ConvexPolygon: a validated, strictly convex, counter-clockwise polygon with a name.
//
// Validation decides every combinatorial property exactly (filtered predicates), whatever
// policy the caller later computes with: at least 3 vertices, finite coordinates, no repeated
// vertex (so no zero-length edge), every turn strictly left (no collinear vertex), and edge
// directions that wind exactly once (no star-shaped self-overlap). A clockwise polygon is an
// error unless the caller asks for VertexOrder::normalise, which reverses it and records that
// it did (reversed()). A violation throws InvalidPolygon naming the polygon and the vertex.

#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

class InvalidPolygon : public std::invalid_argument {
 public:
  enum class Reason { too_few_vertices, non_finite, repeated_vertex, collinear, clockwise, not_convex };

  // vertex < 0 when the problem is the polygon as a whole.
  InvalidPolygon(std::string polygon, std::ptrdiff_t vertex, Reason reason, const std::string& what);

  const std::string& polygon() const noexcept { return polygon_; }
  std::ptrdiff_t vertex() const noexcept { return vertex_; }
  Reason reason() const noexcept { return reason_; }

 private:
  std::string polygon_;
  std::ptrdiff_t vertex_;
  Reason reason_;
};

enum class VertexOrder { require_ccw, normalise };

class ConvexPolygon {
 public:
  // Throws InvalidPolygon. `name` appears in every message ("pairs[3].cp", "block 'slider'").
  static ConvexPolygon make(std::string name, std::vector<Point2> vertices,
                            VertexOrder order = VertexOrder::require_ccw);

  // Replaces the vertices by `vertices`, validated as make() does, keeping the name. A valid
  // counter-clockwise polygon is checked in one pass and copied into the existing storage: no
  // allocation once the capacity suffices, which is what a host evaluating pair after pair
  // needs. Anything else (an invalid polygon, or a clockwise one under normalise) goes through
  // make(), which allocates to diagnose or reverse. Throws InvalidPolygon; on a throw the
  // polygon is unchanged.
  void assign(std::span<const Point2> vertices, VertexOrder order = VertexOrder::require_ccw);

  const std::string& name() const noexcept { return name_; }
  std::span<const Point2> vertices() const noexcept { return vertices_; }
  std::size_t size() const noexcept { return vertices_.size(); }
  const Point2& operator[](std::size_t i) const noexcept { return vertices_[i]; }
  std::size_t next(std::size_t i) const noexcept { return i + 1 == size() ? 0 : i + 1; }
  std::size_t prev(std::size_t i) const noexcept { return i == 0 ? size() - 1 : i - 1; }
  // True when the input was clockwise and VertexOrder::normalise reversed it.
  bool reversed() const noexcept { return reversed_; }

 private:
  ConvexPolygon(std::string name, std::vector<Point2> vertices, bool reversed)
      : name_(std::move(name)), vertices_(std::move(vertices)), reversed_(reversed) {}

  std::string name_;
  std::vector<Point2> vertices_;
  bool reversed_ = false;
};

// Radius of the largest circle inside a strictly convex CCW polygon, m. The centre (x, y) and
// radius r maximise r subject to dist(p, edge line k) >= r for every edge k, a linear program in
// (x, y, r) whose optimum sits where three constraints are tight: every triple of edge lines is
// solved and the largest feasible r kept (O(n^4), for the few vertices of a block). Accurate to
// ~1e-14 relative in a frame at the first vertex, so far from the origin too.
double inscribed_radius(std::span<const Point2> polygon);

}  // namespace rockcontact::kernel
