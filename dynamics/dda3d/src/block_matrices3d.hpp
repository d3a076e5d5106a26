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
//
// ## Central moments
// A block is a union of convex parts moving as one body (a non-convex block is several parts).
// Its moments are the sums of its parts' moments about one point o = the first vertex of its
// first part (kernel::moments_about: the divergence theorem in the frame of o). The global
// moments of kernel::moments() would lose the central ones to cancellation (of a 1 m block
// 10^6 m out, about 3 digits survive); about o they do not, and the central second moments
// follow by the parallel-axis relation
//   S_ij = ∫ (x_i - c_i)(x_j - c_j) dV = m_ij - m_i m_j / V,
// c = o + m / V, over distances of block size (cancellation of a few bits at most).
//
// ## Mass matrix, M = rho ∫ T^T T dV (the inertia term of eq. 13; Shi's 3D DDA)
// Columns of T: t_u, t_v, t_w the unit vectors, t_rx = (0, -Z, Y), t_ry = (Z, 0, -X),
// t_rz = (-Y, X, 0), t_ex = (X, 0, 0), t_ey = (0, Y, 0), t_ez = (0, 0, Z),
// t_gyz = (0, Z, Y) / 2, t_gzx = (Z, 0, X) / 2, t_gxy = (Y, X, 0) / 2; M_ij = rho ∫ t_i . t_j dV.
// About the centroid the first moments vanish, so the translation block is rho V I and
// decouples from the rest; with S the central second moments (Sxx = ∫ X² dV, Sxy = ∫ X Y dV...):
//            rx        ry        rz       ex    ey    ez    gyz        gzx        gxy
//   rx   Syy+Szz   -Sxy      -Szx       0    -Syz   Syz  (Syy-Szz)/2  Sxy/2     -Szx/2
//   ry             Szz+Sxx   -Syz       Szx   0    -Szx  -Sxy/2     (Szz-Sxx)/2  Syz/2
//   rz                       Sxx+Syy   -Sxy   Sxy   0     Szx/2     -Syz/2     (Sxx-Syy)/2
//   ex                                  Sxx   0     0     0          Szx/2      Sxy/2
//   ey                                        Syy   0     Syz/2      0          Sxy/2
//   ez                                              Szz   Syz/2      Szx/2      0
//   gyz                                                  (Syy+Szz)/4 Sxy/4      Szx/4
//   gzx                                                             (Szz+Sxx)/4 Syz/4
//   gxy                                                                        (Sxx+Syy)/4
// times rho (symmetric). The (rx, ry, rz) block is the inertia tensor about the centroid; a
// rigid block uses the leading 6x6 block. Mass is conserved as in 2D: rho = mass / V with the
// mass fixed at the start and V the current volume.
//
// ## Elastic stiffness (eq. 13's elastic term), strain energy ½ V εᵀ C ε, so K = V C on the
// strain unknowns (ex, ey, ez, gyz, gzx, gxy), with engineering shear strains:
//   C = [ λ+2μ  λ     λ     0  0  0 ]     λ = E ν / ((1 + ν)(1 - 2ν))
//       [ λ     λ+2μ  λ     0  0  0 ]     μ = E / (2 (1 + ν))  (the shear modulus)
//       [ λ     λ     λ+2μ  0  0  0 ]
//       [ 0     0     0     μ  0  0 ]
//       [ 0     0     0     0  μ  0 ]
//       [ 0     0     0     0  0  μ ]
//
// ## Configuration update
// Eq. 10 is the first-order map of the step; applied literally to the vertices, the rotation
// part I + [r]x has determinant 1 + |r|², so a spinning block grows by that factor each step
// (seed 001 §5.2; DESIGN.md, Dynamics). The vertices are moved instead by
//   x -> c + (u0, v0, w0) + R(r) (I + ε) (x - c),
//   R(r) = I + (sin θ / θ) [r]x + ((1 - cos θ) / θ²) [r]x²,   θ = |r|   (Rodrigues),
//   ε = [[ex, gxy/2, gzx/2], [gxy/2, ey, gyz/2], [gzx/2, gyz/2, ez]],
// the exact rotation by the rotation vector r: a rigid step keeps the volume to rounding. It is
// evaluated as x + (t + G (x - c)) with G = R (I + ε) - I formed without cancelling against I,
// so a pure translation moves every vertex by exactly fl(x + t) and a small step keeps its digits.
// The rotation since the start is kept as a matrix, R_total <- R(r) R_total, and reported as a
// rotation vector (angle in [0, π] times the unit axis) by a log map accurate near 0 and near π.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
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

using Matrix12 = Eigen::Matrix<double, dof3d, dof3d>;
using Vector12 = Eigen::Matrix<double, dof3d, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct CentralMoments3d {
  double volume = 0.0;                                 // m³
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // m
  // second(i, j) = ∫ (x_i - c_i)(x_j - c_j) dV, m⁵, symmetric.
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};

// Volume, centroid and central second moments of the union of `parts` (non-empty, disjoint
// interiors), integrated in the frame of the first vertex of parts[0] (see above).
CentralMoments3d central_moments3d(std::span<const kernel::ConvexPolyhedron> parts);

// M = rho ∫ T^T T dV (kg, kg m, kg m²) for a block of `mass` kg, rho = mass / volume (above).
// A rigid block uses topLeftCorner<6, 6>().
Matrix12 mass_matrix(const CentralMoments3d& m, double mass);

// C (Pa) mapping (ex, ey, ez, gyz, gzx, gxy) to (sx, sy, sz, tyz, tzx, txy); E > 0 (Pa),
// -1 < nu < 1/2.
Matrix6 elasticity_matrix3d(double youngs_modulus, double poisson_ratio);

// K (N m) with V C in the strain rows and columns (6..11), zero elsewhere: the strain energy of
// increments D is ½ Dᵀ K D = ½ V εᵀ C ε. Rigid blocks have none.
Matrix12 elastic_stiffness(const Matrix6& elasticity, double volume);

// The generalized gravity load (N): mass g on (u0, v0, w0), zero on the rest (the moment of a
// uniform load about the centroid and its work in a constant strain vanish there). A rigid
// block uses head<6>().
Vector12 gravity_load(double mass, const Eigen::Vector3d& g);

// R(r), Rodrigues' formula above; r in rad (any length).
Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& r);

// The rotation vector of the rotation matrix R: angle θ in [0, π] times the unit axis, inverse
// of rotation_matrix() for |r| < π (at θ = π it returns π a or -π a, the same rotation). With
// v = (R32 - R23, R13 - R31, R21 - R12) / 2 = sin θ a and cos θ = (trace R - 1) / 2:
//   θ = atan2(|v|, cos θ), accurate to rounding at every angle;
//   cos θ >= 0: a = v / |v| (v has its full relative precision there);
//   cos θ < 0:  a from the symmetric part, (R + Rᵀ) / 2 - cos θ I = (1 - cos θ) a aᵀ, its
//               largest column normalized (1 - cos θ >= 1, no cancellation), signed by v.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& rotation);

// R(r) R_total, re-orthonormalized by one Newton–Schulz step Q (3 I - QᵀQ) / 2, which squares
// the departure from orthogonality, so rounding does not accumulate in it over many steps.
Eigen::Matrix3d accumulate_rotation(const Eigen::Matrix3d& total, const Eigen::Vector3d& r);

// The map of one step: x -> x + translation + gradient (x - centroid).
struct StepMap {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();     // m, at the start of the step
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // (u0, v0, w0), m
  Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();     // R(r) (I + ε) - I, dimensionless
};

// The step map of increments `d` (6 for a rigid block, 12 otherwise, ordered as D above) for a
// block whose centroid is `centroid` at the start of the step.
StepMap step_map(const Eigen::Vector3d& centroid, const Eigen::Ref<const Eigen::VectorXd>& d);

kernel::Point3 apply(const StepMap& map, const kernel::Point3& x);

// The parts with every vertex moved by `map`, re-validated by ConvexPolyhedron::moved (faces
// and vertex ids kept); throws kernel::InvalidPolyhedron if a step turned a part inside out.
std::vector<kernel::ConvexPolyhedron> moved_parts(std::span<const kernel::ConvexPolyhedron> parts,
                                                  const StepMap& map);

}  // namespace rockcontact::dynamics::detail
