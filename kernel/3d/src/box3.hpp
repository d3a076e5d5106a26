#pragma once
// The axis-aligned box of some convex parts, as the 3D kernel's constructions bound their work
// with it: the contact constraints (contact_constraints.cpp) and the faces cut blocks share
// (block_cutting.cpp). Private to kernel/3d/src.

#include <algorithm>
#include <cmath>
#include <span>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

namespace rockcontact::kernel::detail {

// Exact: comparisons of the input doubles.
struct Box3 {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};

  void add(std::span<const ConvexPolyhedron> parts) {
    for (const ConvexPolyhedron& part : parts) {
      for (const Point3& p : part.vertices()) {
        const double c[3] = {p.x, p.y, p.z};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
      }
    }
  }
  void add(const Box3& o) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], o.lo[k]), hi[k] = std::max(hi[k], o.hi[k]);
  }
  double size() const { return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
  // Do the boxes' interiors meet? Two convex parts can overlap only where they do.
  bool interiors_meet(const Box3& o) const {
    for (int k = 0; k < 3; ++k) {
      if (!(lo[k] < o.hi[k] && o.lo[k] < hi[k])) return false;
    }
    return true;
  }
  // Do the boxes meet, each grown by `slack`? Two parts can share a face only where they do.
  bool meets(const Box3& o, double slack) const {
    for (int k = 0; k < 3; ++k) {
      if (lo[k] > o.hi[k] + 2 * slack || o.lo[k] > hi[k] + 2 * slack) return false;
    }
    return true;
  }
};

inline Box3 box_of(std::span<const ConvexPolyhedron> parts) {
  Box3 box;
  box.add(parts);
  return box;
}

}  // namespace rockcontact::kernel::detail
