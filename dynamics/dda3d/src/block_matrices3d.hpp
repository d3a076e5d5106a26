#pragma once
// Per-block matrices of the implicit 3D DDA (seed 001 §3.1, eq. 9-13; the classic 3D DDA of
// Shi): the displacement matrix T of a point, and what a block contributes to the global
// equilibrium equation. Private to dynamics/dda3d; Eigen-typed.
//
// Each block carries 12 unknowns per step (eq. 9), the increments over the step of
//   D = (u0, v0, w0, rx, ry, rz, ex, ey, ez, gyz, gzx, gxy)
// the translation of the centroid (m), the rotation about x, y, z (rad, small over a step) and
// the constant strain (engineering shear strains); a rigid block uses the first 6 only. A point
// at offset (X, Y, Z) = x - c from the centroid c moves by u = T(x) D (eq. 10-12):
//   u = u0           + Z ry - Y rz + X ex               + Z gzx / 2 + Y gxy / 2
//   v = v0 - Z rx           + X rz          + Y ey      + Z gyz / 2             + X gxy / 2
//   w = w0 + Y rx - X ry                         + Z ez + Y gyz / 2 + X gzx / 2
// (the rotation part is r x (X, Y, Z); the strain part the symmetric strain tensor times it).

#include <Eigen/Core>

#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics::detail {

inline constexpr int dof3d = 12;        // a deformable block's unknowns
inline constexpr int rigid_dof3d = 6;   // a rigid block's: translation and rotation

using Matrix3x12 = Eigen::Matrix<double, 3, dof3d>;

// T at offset (X, Y, Z) = x - centroid; the first 6 columns are a rigid block's T.
inline Matrix3x12 displacement_matrix(const kernel::Point3& offset) {
  const double X = offset.x, Y = offset.y, Z = offset.z;
  Matrix3x12 t;
  //    u0   v0   w0   rx   ry   rz   ex   ey   ez   gyz      gzx      gxy
  t << 1.0, 0.0, 0.0, 0.0, Z, -Y, X, 0.0, 0.0, 0.0, Z / 2, Y / 2,  //
      0.0, 1.0, 0.0, -Z, 0.0, X, 0.0, Y, 0.0, Z / 2, 0.0, X / 2,   //
      0.0, 0.0, 1.0, Y, -X, 0.0, 0.0, 0.0, Z, Y / 2, X / 2, 0.0;
  return t;
}

}  // namespace rockcontact::dynamics::detail
