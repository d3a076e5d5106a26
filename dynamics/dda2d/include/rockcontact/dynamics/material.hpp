#pragma once
// The elastic material of a block, shared by the 2D and 3D engines.

namespace rockcontact::dynamics {

struct Material {
  double density = 2000.0;        // kg/m³, > 0
  double youngs_modulus = 1.0e9;  // Pa, > 0
  double poisson_ratio = 0.25;    // -, in (-1, 0.5)
};

}  // namespace rockcontact::dynamics
