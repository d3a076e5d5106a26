#pragma once
// Area moments of a simple polygon, for the DDA mass matrix (seed 000 §2):
//   S = ∫ dA,  Sx = ∫ x dA,  Sy = ∫ y dA,  Sxx = ∫ x² dA,  Syy = ∫ y² dA,  Sxy = ∫ x y dA.
// Computed by Green's theorem edge by edge in a frame centred on the first vertex (so a
// polygon far from the origin loses no digits to cancellation) and shifted back exactly by the
// parallel-axis relations. Positive for a CCW polygon.

#include <span>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

struct PolygonMoments {
  double S = 0.0;    // m²
  double Sx = 0.0;   // m³
  double Sy = 0.0;   // m³
  double Sxx = 0.0;  // m⁴
  double Syy = 0.0;  // m⁴
  double Sxy = 0.0;  // m⁴
  Point2 centroid() const { return {Sx / S, Sy / S}; }
};

PolygonMoments compute_moments(std::span<const Point2> vertices);

}  // namespace rockcontact::kernel
