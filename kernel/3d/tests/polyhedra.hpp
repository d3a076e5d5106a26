#pragma once
// Small polyhedra with known geometry for the 3D metric tests (distance, penetration, contact
// set), and readers of the contact3d reference numbers.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::testing {

using kernel::ConvexPolyhedron;
using kernel::Point3;

// The prism over a convex polygon (x, y counter-clockwise seen from above) from z0 to z1.
inline ConvexPolyhedron prism(const std::string& name, const std::vector<std::pair<double, double>>& base,
                              double z0, double z1) {
  const auto n = static_cast<std::uint32_t>(base.size());
  std::vector<Point3> vertices;
  for (const auto& [x, y] : base) vertices.push_back({x, y, z0});
  for (const auto& [x, y] : base) vertices.push_back({x, y, z1});
  std::vector<ConvexPolyhedron::Face> faces(2);
  for (std::uint32_t i = 0; i < n; ++i) {
    faces[0].push_back(n - 1 - i);
    faces[1].push_back(n + i);
    const std::uint32_t j = (i + 1) % n;
    faces.push_back({i, j, n + j, n + i});
  }
  return ConvexPolyhedron::make(name, std::move(vertices), std::move(faces));
}

// A tetrahedron whose edge from (0.5, 1.5, 0.5) to (0.5, 0.5, 1.5) crosses the top back edge
// (y = 1, z = 1) of the unit cube at (0.5, 1, 1), shifted by (0, -s, -s): touching at s = 0,
// overlapping for s > 0, along the edges' common normal (0, 1, 1) / sqrt 2.
inline ConvexPolyhedron crossing_tetrahedron(const std::string& name, double s) {
  return ConvexPolyhedron::make(
      name, {{0.5, 1.5 - s, 0.5 - s}, {0.5, 0.5 - s, 1.5 - s}, {0.0, 2.0 - s, 2.0 - s}, {1.0, 2.0 - s, 2.0 - s}},
      {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

// The tetrahedron of four points, its faces ordered CCW from outside; nullopt when coplanar.
inline std::optional<ConvexPolyhedron> tetrahedron(const std::string& name, std::vector<Point3> v) {
  const kernel::Sign s = kernel::orient3d<kernel::Exact>(v[0], v[1], v[2], v[3]);
  if (s == kernel::Sign::zero) return std::nullopt;
  if (s == kernel::Sign::positive) std::swap(v[1], v[2]);
  return ConvexPolyhedron::make(name, std::move(v), {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

// An exact symmetry of the coordinate axes: coordinate i of the image is sign[i] times
// coordinate axis[i] of the point.
struct AxisMap {
  std::array<int, 3> axis{0, 1, 2};
  std::array<double, 3> sign{1, 1, 1};

  Point3 operator()(const Point3& p) const {
    const double c[3] = {p.x, p.y, p.z};
    return {sign[0] * c[axis[0]], sign[1] * c[axis[1]], sign[2] * c[axis[2]]};
  }
  // Reverses orientation (an odd permutation times an even number of flips, or the converse)?
  bool reverses() const {
    const int inversions = (axis[0] > axis[1]) + (axis[0] > axis[2]) + (axis[1] > axis[2]);
    return (inversions % 2 == 1) != (sign[0] * sign[1] * sign[2] < 0);
  }
};

// The image of p under m, faces reversed when m reverses orientation so they stay CCW from
// outside.
inline ConvexPolyhedron mapped(const ConvexPolyhedron& p, const AxisMap& m) {
  std::vector<Point3> vertices;
  for (const Point3& v : p.vertices()) vertices.push_back(m(v));
  std::vector<ConvexPolyhedron::Face> faces(p.faces().begin(), p.faces().end());
  if (m.reverses()) {
    for (auto& f : faces) std::reverse(f.begin(), f.end());
  }
  return ConvexPolyhedron::make(p.name() + " mapped", std::move(vertices), std::move(faces));
}

inline ConvexPolyhedron translated(const ConvexPolyhedron& p, Point3 d) {
  std::vector<Point3> vertices;
  for (const Point3& v : p.vertices()) vertices.push_back({v.x + d.x, v.y + d.y, v.z + d.z});
  return ConvexPolyhedron::make(p.name() + " moved", std::move(vertices),
                                std::vector<ConvexPolyhedron::Face>(p.faces().begin(), p.faces().end()));
}

// A reference number (a decimal string of 50 digits), rounded to double.
inline double number(const nlohmann::json& j) { return std::stod(j.get<std::string>()); }

inline Point3 point(const nlohmann::json& j) { return {number(j.at(0)), number(j.at(1)), number(j.at(2))}; }

inline double distance(const Point3& p, const Point3& q) {
  return std::hypot(p.x - q.x, p.y - q.y, p.z - q.z);
}

// The README's tolerance for a distance or a depth: 1e-9 relative, or 1e-12 scale absolute
// near zero (the reference is exact; both bounds are far above a correctly computed double's
// error and far below any wrong feature choice on these pairs).
inline bool metric_matches(double value, double reference, double scale) {
  return std::fabs(value - reference) <= std::max(1e-9 * std::fabs(reference), 1e-12 * scale);
}

}  // namespace rockcontact::testing
