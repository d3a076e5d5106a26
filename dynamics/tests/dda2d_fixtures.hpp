#pragma once
// Small builders shared by the DDA tests: blocks, the frictionless contact of Table 4 row 4.1
// (kn 1e7 Pa, H 1 m), step parameters and the energy balance. Header-only, test code only.

#include <algorithm>
#include <cmath>
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

// The energy balance of dda2d.hpp: Energies::total() keeps its start value. Records, over the
// instants it is given, the largest departure of total() from the start and the largest
// magnitude any single term reached, both J/m.
class EnergyBalance {
 public:
  explicit EnergyBalance(const Energies& start) : start_(start.total()) { record(start); }

  void record(const Energies& e) {
    drift_ = std::max(drift_, std::fabs(e.total() - start_));
    for (const double term : {e.kinetic, e.gravitational, e.strain, e.contact, e.friction_dissipated,
                              e.damping_dissipated}) {
      largest_ = std::max(largest_, std::fabs(term));
    }
  }

  double drift() const { return drift_; }
  double largest_term() const { return largest_; }
  double ratio() const { return drift_ / largest_; }  // the imbalance relative to the largest term

 private:
  double start_;
  double drift_ = 0.0;
  double largest_ = 0.0;
};

}  // namespace rockcontact::dynamics::testing
