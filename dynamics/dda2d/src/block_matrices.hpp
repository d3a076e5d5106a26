#pragma once
// Per-block matrices of 2D DDA (seed 000 §2, eq. 3, 5a, 5b) and the block measures the
// stability estimates use. Internal to rockcontact_dynamics.
//
// ## T(x, y) (eq. 3), relative to the centroid (x, y = offsets from it)
//   T = [ 1  0  -y  x  0  y/2 ]     d = (u0, v0, r0, ex, ey, gxy)
//       [ 0  1   x  0  y  x/2 ]
//
// ## Mass matrix (eq. 5a), M = rho ∫ T^T T dA
// The columns of T are c0 = (1,0), c1 = (0,1), c2 = (-y,x), c3 = (x,0), c4 = (0,y),
// c5 = (y/2,x/2); M_ij = rho ∫ c_i . c_j dA. With S the area, S_x = ∫ x dA, S_xx = ∫ x² dA etc.:
//   M = rho [ S    0    -S_y         S_x    0     S_y/2          ]
//           [ 0    S     S_x         0      S_y   S_x/2          ]
//           [-S_y  S_x   S_xx+S_yy  -S_xy   S_xy  (S_xx-S_yy)/2  ]
//           [ S_x  0    -S_xy        S_xx   0     S_xy/2         ]
//           [ 0    S_y   S_xy        0      S_yy  S_xy/2         ]
//           [ S_y/2 S_x/2 (S_xx-S_yy)/2 S_xy/2 S_xy/2 (S_xx+S_yy)/4 ]
// About the centroid the first moments vanish (S_x = S_y = 0): the translation block is rho S I
// and decouples from the 4x4 block of (r0, ex, ey, gxy), whose entries are the central second
// moments I_xx, I_yy, I_xy. Rigid blocks keep (u0, v0, r0) only: diag(m, m, rho (I_xx + I_yy)).
// Mass is conserved: rho = m / S with m fixed at the start and S the current area, so a
// strained block keeps its mass (and its momentum) exactly.
//
// ## Elastic stiffness (eq. 5b), K = ∫ E dA = S E on (ex, ey, gxy), gxy the engineering shear:
//   plane stress  E/(1-nu²)          [ 1     nu    0          ]
//                                    [ nu    1     0          ]
//                                    [ 0     0     (1-nu)/2   ]
//   plane strain  E/((1+nu)(1-2nu))  [ 1-nu  nu    0          ]
//                                    [ nu    1-nu  0          ]
//                                    [ 0     0     (1-2nu)/2  ]

#include <array>
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::dynamics::detail {

using Vector6 = std::array<double, 6>;

struct CentralMoments {
  double area = 0.0;  // m²
  Point2 centroid;    // m
  double ixx = 0.0;   // ∫ (x - xc)² dA, m⁴
  double iyy = 0.0;   // ∫ (y - yc)² dA, m⁴
  double ixy = 0.0;   // ∫ (x - xc)(y - yc) dA, m⁴
};

// Moments of a CCW polygon, integrated relative to its first vertex (`scratch` holds the shifted
// vertices) so that a block far from the origin loses no digits.
CentralMoments central_moments(std::span<const Point2> vertices, std::vector<Point2>& scratch);

// The (r0, ex, ey, gxy) block of M for a block of mass `mass` (kg/m): density mass / area.
Eigen::Matrix4d rotation_strain_mass(const CentralMoments& m, double mass);

// Rigid blocks: rho (I_xx + I_yy), kg m²/m.
double rotational_inertia(const CentralMoments& m, double mass);

// (sigma_x, sigma_y, tau_xy) = E (ex, ey, gxy), Pa.
Eigen::Matrix3d elasticity_matrix(const Material& material, PlaneMode plane);

// T(x, y)^T f for a point at offset r from the centroid: the generalized force of f (N/m).
Vector6 transform_transpose(Vector2 r, Vector2 f);

// T(x, y) d for a point at offset r from the centroid (eq. 3): its displacement for d a
// displacement, its velocity for d a velocity.
Vector2 transform(Vector2 r, const Vector6& d);

// Largest compliance of a point of the block, max over vertices of the largest eigenvalue of
// T M^-1 T^T (1/kg per metre of thickness): the acceleration of a boundary point per unit force
// there. It is a convex quadratic of the point, so its maximum over the polygon is at a vertex.
double max_vertex_compliance(std::span<const Point2> vertices, const CentralMoments& m,
                             double mass, bool rigid);

// The largest omega² (rad²/s²) of the strain modes: the largest generalized eigenvalue of
// (K, M) on (r0, ex, ey, gxy), K = S E on the strain DOFs.
double elastic_omega_squared(const CentralMoments& m, double mass, const Eigen::Matrix3d& elasticity);

double perimeter(std::span<const Point2> vertices);  // m

}  // namespace rockcontact::dynamics::detail
