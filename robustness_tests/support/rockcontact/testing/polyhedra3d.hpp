#pragma once
// Convex polyhedra with known geometry for the 3D tests: boxes, unit cubes and octahedra.

#include <string>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

namespace rockcontact::testing {

using kernel::ConvexPolyhedron;
using kernel::Point3;

// The axis-aligned box [lo, hi], faces counter-clockwise seen from outside.
inline ConvexPolyhedron box(const std::string& name, Point3 lo, Point3 hi) {
  return ConvexPolyhedron::make(
      name,
      {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}},
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
}

inline ConvexPolyhedron unit_cube_at(const std::string& name, Point3 o) {
  return box(name, o, {o.x + 1, o.y + 1, o.z + 1});
}

// Vertices at c +- r along each axis.
inline ConvexPolyhedron octahedron(const std::string& name, Point3 c, double r) {
  return ConvexPolyhedron::make(
      name,
      {{c.x + r, c.y, c.z}, {c.x - r, c.y, c.z}, {c.x, c.y + r, c.z}, {c.x, c.y - r, c.z}, {c.x, c.y, c.z + r},
       {c.x, c.y, c.z - r}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

}  // namespace rockcontact::testing
