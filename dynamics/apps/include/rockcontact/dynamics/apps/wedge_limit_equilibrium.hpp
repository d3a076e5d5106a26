#pragma once
// The limit-equilibrium factor of safety of a rock wedge resting on two joint planes: the
// analytic reference of seed 001 §6.1 (joints 50°/110° and 55°/240°, φ = 40° on both,
// FS = 2.198 by its eq. 51), against which the 3D DDA's `safety-factor` is validated.
//
// Method: Hoek & Bray, Rock Slope Engineering (3rd ed., 1981), ch. 8 "Wedge failure", in the
// vector form of its comprehensive solution. The wedge is rigid and rests on both planes; the
// weight W is resolved into normal reactions N_A, N_B on the planes and a driving force D along
// the line of intersection, and the factor of safety is the ratio of the Mohr-Coulomb strength
// the reactions mobilise to D.
//
// Conventions (those of block cutting, kernel/3d/block_cutting.hpp): axes x East, y North,
// z Up; dip δ in [0, 90] degrees, dip direction α in [0, 360) degrees clockwise from North.
//   n = (sin δ sin α, sin δ cos α, cos δ)          the plane's upward unit normal
//   m = n_A · n_B                                  cos of the angle between the normals
//   i = ±(n_A × n_B) / |n_A × n_B|,  i_z < 0       the line of intersection, pointing down it
//   plunge ψ_i = asin(−i_z),  trend = atan2(i_x, i_y) in [0, 360)   (0 when i is vertical)
// The weight (0, 0, −W) balances the reactions N_A n_A + N_B n_B and the shear along i:
//   N_A = W (n_Az − m n_Bz) / (1 − m²),   N_B = W (n_Bz − m n_Az) / (1 − m²),   D = W sin ψ_i.
// With n_z = cos ψ (ψ the dip) this is Hoek & Bray's friction-only form, seed 001 eq. 51:
//   FS = A tan φ_A + B tan φ_B + (c_A S_A + c_B S_B) / D,
//   A = (cos ψ_A − m cos ψ_B) / ((1 − m²) sin ψ_i),   B = (cos ψ_B − m cos ψ_A) / ((1 − m²) sin ψ_i),
// A and B functions of the orientations alone (S the contact areas, c the cohesions).
//
// Kinematic check (Hoek & Bray's contact check): a reaction that comes out <= 0 means the
// wedge leaves that plane and slides on the other one alone, down its dip vector:
//   plane_a: N_A = W cos ψ_A, N_B = 0, D = W sin ψ_A, FS = tan φ_A / tan ψ_A + c_A S_A / D,
// and symmetrically for plane_b. The switch is continuous (at N_B = 0 the weight lies in the
// plane of n_A and i, so i is A's dip vector and both formulas agree), so it needs no
// tolerance. Under gravity alone both reactions are <= 0 only if both planes are vertical
// (n_Az = n_Bz = 0): then neither plane carries the wedge (lift_off, FS = 0).
//
// Where this departs from Hoek & Bray: it is dry (no water pressure on the planes, as in seed
// 001 §6.1) and takes no slope face, upper face or tension crack. So it does NOT check that the
// wedge is removable or that the line of intersection daylights in the slope face: the caller
// states that the wedge exists, rests on top of both planes (on the side their upward normals
// point to) and is free to slide; the contact areas S_A, S_B, which the slope geometry would
// give, are inputs (only the cohesion terms use them).

#include <ostream>
#include <string_view>

#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics {

// The angle thresholds below which the geometry is refused. The line i has an absolute error
// of a few units of 2^-53 divided by |n_A × n_B| = sin θ (θ the angle between the normals).
// Refusing sin θ < 1e-6 keeps that error below 1e-9, far under the 1e-6 refused for sin ψ_i,
// so the sign of the plunge of an accepted line is certain. Raising them refuses nearly
// parallel planes or nearly horizontal lines whose FS is large but well defined.
inline constexpr double wedge_parallel_sine = 1e-6;  // sin θ, dimensionless (θ ≈ 5.7e-5 degrees)
inline constexpr double wedge_plunge_sine = 1e-6;    // sin ψ_i, dimensionless (ψ_i ≈ 5.7e-5 degrees)

struct WedgeJoint {
  double dip_deg = 0.0;             // degrees, in [0, 90]: 0 horizontal, 90 vertical
  double dip_direction_deg = 0.0;   // degrees, in [0, 360), clockwise from North (+y); 90 East
  double friction_angle_deg = 0.0;  // degrees, in [0, 90)
  double cohesion_pa = 0.0;         // Pa, finite >= 0
  double area = 0.0;                // m², finite >= 0: the wedge's contact area on this plane
  friend bool operator==(const WedgeJoint&, const WedgeJoint&) = default;
};

enum class WedgeMode {
  wedge,     // sliding along the line of intersection on both planes
  plane_a,   // N_B <= 0: sliding on plane A alone, down its dip vector
  plane_b,   // N_A <= 0: sliding on plane B alone, down its dip vector
  lift_off,  // both planes vertical: neither carries the wedge, FS = 0
};

std::string_view to_string(WedgeMode mode);
std::ostream& operator<<(std::ostream& out, WedgeMode mode);  // to_string(mode)

struct WedgeLimitEquilibrium {
  double factor_of_safety = 0.0;    // dimensionless: resisting / driving force along `sliding`
  WedgeMode mode = WedgeMode::wedge;
  double coefficient_a = 0.0;       // eq. 51's A, dimensionless (FS's friction part is
  double coefficient_b = 0.0;       // A tan φ_A + B tan φ_B); 0 for a plane the wedge left
  double normal_reaction_a = 0.0;   // N, >= 0: the plane's push on the wedge along normal_a
  double normal_reaction_b = 0.0;   // N, >= 0
  double driving_force = 0.0;       // N, >= 0: the weight's component along `sliding`
  kernel::Point3 normal_a;          // the upward unit normal of plane A
  kernel::Point3 normal_b;          // the upward unit normal of plane B
  kernel::Point3 intersection;      // unit vector along the line of intersection, z < 0
  double plunge_deg = 0.0;          // degrees, in (0, 90]: of `intersection` below horizontal
  double trend_deg = 0.0;           // degrees, in [0, 360), clockwise from North; 0 if vertical
  kernel::Point3 sliding;           // unit vector the wedge slides along: `intersection` in
                                    // wedge mode, the plane's dip vector in plane_a / plane_b
};

// The factor of safety of a dry wedge of weight `weight_n` (N, finite > 0) on joints `a` and
// `b` (header). Throws std::invalid_argument naming the field ("joint_a.dip_deg", "weight_n",
// "joint_a, joint_b" for parallel planes or a line of intersection that does not plunge) and
// what was expected.
WedgeLimitEquilibrium wedge_factor_of_safety(const WedgeJoint& a, const WedgeJoint& b, double weight_n);

}  // namespace rockcontact::dynamics
