#pragma once
// Stiff and extreme dynamics of the explicit 2D DDA (dynamics/dda2d.hpp): the scenarios of the
// project's issue 5, shared by the Boost.Test suite (short runs) and the table executable (full
// runs). Each scenario returns its measured figures next to an analytic reference computed
// here, independently of the engine:
//
//   * resting block (kn/E sweep and dt sweep): a deformable unit square released at rest,
//     just touching a fixed base, under gravity. By symmetry only (v0, ex, ey) move; the
//     contact is a spring on the face displacement v0 - (l/2) ey, so the motion is that of a
//     3-DOF linear system (M, K) whose modes, static state and Verlet energy bound are computed
//     here in closed form (seed 000 eq. 5a for M, the plane-stress E-matrix for K);
//   * squeezed block: a deformable square pressed by four fixed blocks, whose dilatation mode
//     carries both the elastic and the contact stiffness at once (the case that made the
//     engine's estimate add the two bounds instead of taking the larger; see squeezed_block);
//   * mass ratio: two rigid squares stacked on a fixed base, one 10^0..10^6 times heavier;
//   * resting stack: ten rigid squares placed at their static equilibrium, run for 10^6 steps;
//   * the §5.2-§5.3 scenes of seed 000 (5° triangles, 0.01 m edges) from examples/scenes with
//     kn multiplied by 1, 10, 100.
//
// The face-on-face force of the potential law (seed 000 eq. 12-14, the shortest-exit
// potential phi = kn d_exit / H): the overlap of a face of length L with a wider block is the
// rectangle [0, L] x [0, d]. The net force on one block is the area integral of d(phi_A -
// phi_B)/dy over it; the wide block's exit distance is d - y everywhere, the square's is
// min(y, x, L - x), whose y-derivative vanishes in the two corner triangles of area d²/2. So
//     F = kn / H (2 L d - d²)      against a wider block,
//     F = 2 kn / H (L d - d²)      between two faces of equal length L, corners aligned,
// and the static depth under a load W is the smaller root of the quadratic.

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>

namespace rockcontact::stiff {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Allowances, shared by the test and the table so that both judge alike:
//   * model_energy_allowance (x the model's E_osc): the models are linear, the engine updates
//     the geometry every step (mass matrix from the current moments, face lengths, the law's
//     -d² term), nonlinear terms of the relative size of the strain (m g / (E l) = 2e-5) and of
//     D_s / L; ten times the strain;
//   * period_tolerance (relative, plus D_s / L for the law's softening): crossings are
//     interpolated linearly within a step, an error of order (omega h)² / 8 per crossing over
//     >= 10 crossings in the table (>= 2 in the test);
//   * the 10^-1/3 scaling of §5.2's peak penetration per factor 10 of kn: the overlap of two
//     wedges is self-similar, F = C kn d² / H, so the impact energy C kn d³ / (3 H) fixes
//     d ~ kn^-1/3; the peak is sampled once per step (contact >= 100 steps: (pi / 100)² / 2 =
//     5e-4) and the triangles' strain takes a small, kn-dependent share of the impact: 2 %.
constexpr double model_energy_allowance = 1.0e-4;
constexpr double period_tolerance = 1.0e-3;
constexpr double wedge_scaling_tolerance = 0.02;

// Time step as a fraction of the engine's critical estimate, the default of every scenario
// that does not sweep it: omega h <= 1 for every mode the estimate bounds, so the Verlet
// energy oscillation stays below (omega h / 2)² = 1/4 of each mode's energy.
constexpr double default_dt_fraction = 0.5;

// Static depth, m, of a face of length L (m) under a load W (N/m) against a wider block
// (equal_faces false) or an equal aligned face (true); kn in Pa, H in m.
double static_depth(double W, double L, double kn, double H, bool equal_faces);

// --- resting block -------------------------------------------------------------------------
struct RestingRun {
  double kn_over_e = 0.0;
  double dt = 0.0;           // s
  double dt_estimate = 0.0;  // s, the engine's critical_time_step()
  double dt_model = 0.0;     // s, 2 / omega_max of the 3-DOF model: the true limit
  double static_depth = 0.0;     // m, analytic (header)
  double mean_depth = 0.0;       // m, time average over an integer number of lowest periods
  // m: what the modes leave in that average (linear model, exact for Verlet) plus D_s² / L
  // for the law's -d² term
  double mean_depth_tolerance = 0.0;
  double max_depth = 0.0;        // m, measured
  double max_depth_bound = 0.0;  // m, D_s + sum_k |c_k b.phi_k| of the discrete modal solution
  double period_rigid = 0.0;     // s, 2 pi sqrt(m / k): rigid block on the contact spring
  double period_model = 0.0;     // s, lowest mode of the model under Verlet (discrete)
  double period_measured = nan;  // s, from the centroid's crossings of its mean
  double energy_scale = 0.0;     // J/m, E_osc = ½ x_s^T K x_s, the energy of the oscillation
  double energy_drop = 0.0;      // J/m, max (E0 - E(t)), Verlet's dip
  double energy_rise = 0.0;      // J/m, max (E(t) - E0): zero for a linear Verlet start at rest
  double energy_bound = 0.0;     // J/m, sum_k q_k E_k, q_k = (omega_k h / 2)²
  std::size_t steps = 0;
  double seconds = 0.0;  // wall
};

// E = 1 GPa, nu 0.25, rho 2000, 1 m square on a 3 m x 1 m fixed base, H = 1 m, frictionless,
// kn = kn_over_e * E. dt = dt_fraction * the engine's estimate, duration `periods` lowest
// periods of the model. Throws dynamics::StabilityError as the engine does.
RestingRun resting_block(double kn_over_e, double dt_fraction, double periods);

// The engine's refusal of dt = dt_fraction * estimate for the same scene: the message, or
// empty when it was accepted.
std::string resting_block_refusal(double kn_over_e, double dt_fraction);

// --- squeezed block ------------------------------------------------------------------------
struct SqueezedRun {
  double kn_over_e = 0.0;
  double dt = 0.0;           // s
  double dt_estimate = 0.0;  // s, the engine's estimate (elastic plus contact bound)
  double dt_model = 0.0;     // s, 2 / omega of the dilatation mode (elastic + contact)
  bool refused = false;      // the constructor threw StabilityError
  bool stopped = false;      // step() threw StabilityError
  std::string message;       // of that StabilityError
  std::size_t steps = 0;     // taken (the failing one included)
  double energy_scale = 0.0;  // J/m, E_osc of the dilatation mode
  double energy_rise = 0.0;   // J/m, max (E(t) - E0) over the completed steps
  double energy_drop = 0.0;   // J/m, max (E0 - E(t))
  double seconds = 0.0;
};

// A 1 m deformable square overlapping four fixed blocks by depth = 1e-4 m on every face, no
// gravity, kn/E = 12 H / (28 l (1 - nu)) = 0.571: the ratio at which the elastic bound and the
// contact bound of the engine's estimate are equal, where taking the larger of the two alone
// overestimated the true limit most (0.837 of it: a run diverged at 0.878 of that estimate).
// dt = dt_over_estimate * dt_estimate.
SqueezedRun squeezed_block(double dt_over_estimate, std::size_t steps);

// --- mass ratio ----------------------------------------------------------------------------
struct MassRatioRun {
  double ratio = 0.0;          // heavy mass / light mass
  bool heavy_on_top = false;
  double dt = 0.0, dt_estimate = 0.0;      // s
  double top_static = 0.0, top_mean = 0.0;        // m: top block on the lower one
  double bottom_static = 0.0, bottom_mean = 0.0;  // m: lower block on the base
  double top_tolerance = 0.0, bottom_tolerance = 0.0;  // m, as RestingRun::mean_depth_tolerance
  double top_excursion = 0.0, bottom_excursion = 0.0;  // m, largest |D - D_s| of the model:
                                                       // below D_s, the contacts stay closed
  double max_depth = 0.0;                          // m, engine's max_penetration()
  double energy_scale = 0.0, energy_drop = 0.0, energy_rise = 0.0, energy_bound = 0.0;  // J/m
  std::size_t steps = 0;
  double seconds = 0.0;
};

// Rigid squares on a fixed base, frictionless, kn 1e7 Pa, H 1 m: the heavy one 1 m with rho
// 2000, the light one 0.5 m with 1/ratio of that mass; both start at rest with half their
// static overlaps. Runs `slow_periods` periods of the slow mode of the 2-DOF model.
MassRatioRun mass_ratio(double ratio, bool heavy_on_top, double slow_periods);

// --- resting stack -------------------------------------------------------------------------
struct StackRun {
  std::size_t blocks = 0, steps = 0;
  double dt = 0.0, dt_estimate = 0.0;  // s
  double position_drift = 0.0;   // m, max over blocks and steps of |centroid - start|
  double rotation_drift = 0.0;   // rad, max |rotation|
  double energy_drift = 0.0;     // J/m, max |E(t) - E0|
  double energy_stored = 0.0;    // J/m, the contacts' energy at equilibrium (integral of F)
  double seconds = 0.0;
};

// Ten rigid 1 m squares (rho 2000) on a fixed base, kn 5e7 Pa, kt 1e7 N/m, 30° (seed 000 Table
// 5), H 1 m, each overlap set to its static depth (header): the stack starts at rest at its
// equilibrium, so any motion is numerical.
StackRun resting_stack(std::size_t steps);

// --- seed 000 §5.2-§5.3 with a stiffer contact ---------------------------------------------
struct PaperSceneRun {
  std::string scene;
  double kn_factor = 0.0, kn = 0.0;        // -, Pa
  double dt = 0.0, dt_estimate = 0.0;      // s
  std::size_t steps = 0;
  bool completed = false;
  std::string message;                     // the StabilityError, if any
  double max_penetration = 0.0;            // m
  double impact_energy = 0.0;              // J/m, largest kinetic energy of the run
  double energy_growth = 0.0;              // max (E(t) - E0) / impact_energy
  // m, point asymmetry |c_top + c_bottom| and 1 m x |r_top - r_bottom| (triangles only)
  double asymmetry = nan;
  double rebound_ratio = nan;              // rebound / impact speed (a block named "falling")
  double seconds = 0.0;
};

// Reads `file` (a scene of examples/scenes), multiplies kn (and every interface's kn) by
// kn_factor, sets dt to default_dt_fraction of the engine's estimate and runs `duration`
// seconds (the scene's own duration when not positive).
PaperSceneRun paper_scene(const std::filesystem::path& file, double kn_factor, double duration);

}  // namespace rockcontact::stiff
