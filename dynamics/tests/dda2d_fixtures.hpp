#pragma once
// Small builders shared by the DDA tests: blocks, the frictionless contact of Table 4 row 4.1
// (kn 1e7 Pa, H 1 m) and step parameters. Header-only, test code only.

#include <string>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/dda2d.hpp"

namespace rockcontact::dynamics::testing {

// The CCW square [x0, x0 + side] x [y0, y0 + side].
inline std::vector<Point2> square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

inline BlockSpec block(std::string id, std::vector<Point2> vertices, bool fixed = false) {
  BlockSpec b;
  b.id = std::move(id);
  b.vertices = std::move(vertices);
  b.fixed = fixed;
  return b;
}

// kn in Pa, H in m; no friction.
inline ContactLaw frictionless(double kn = 1.0e7, double H = 1.0) {
  ContactLaw law;
  law.normal.kn = kn;
  law.normal.H = H;
  return law;
}

// dt in s, gravity in m/s² (none by default).
inline DdaParams params(double dt, Vector2 gravity = {0.0, 0.0}) {
  DdaParams p;
  p.dt = dt;
  p.gravity = gravity;
  return p;
}

}  // namespace rockcontact::dynamics::testing
