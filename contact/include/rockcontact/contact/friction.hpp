#pragma once
// Coulomb friction of a 2D contact pair from the accumulated relative displacement of its
// contact point (seed 000 §3.2.5-§3.2.6, eq. 24-26).
//
// A pair keeps one FrictionState from the step it starts overlapping (stick, d = 0) until it
// separates (the record is then dropped). At each instant t_n, with the normal force f_n on CP
// and its unit direction n = f_n / |f_n|:
//   d_nor = (d . n) n,  d_tan = d - d_nor,  s = d_tan / |d_tan|                      (eq. 24)
//   limit = |f_n| tan(phi)
//   stick at t_n-1:  f_t = -kt d_tan           if kt |d_tan| <  limit                (eq. 25)
//                    f_t = -limit s            if kt |d_tan| >= limit
//   slide at t_n-1:  f_t = -limit s            if f_t(n-1) . d_tan <  0              (eq. 26)
//                    otherwise the motion has reversed against the last friction force
//                    and eq. 25 decides again
// f_t acts on CP at the contact point pg and -f_t on TP. Between t_n and t_n+1 the relative
// displacement increment Δd = Δu_CP(pg) - Δu_TP(pg) updates d (§3.2.6): d += Δd after a
// stick step, d = Δd after a sliding step (the spring restarts from the current position).
//
// Known behaviour of this law (the paper's, kept as it is): the update after a sliding step,
// d = Δd, forgets the spring's stretch, and nothing in the contact damps. A pair whose load stays
// below the Coulomb limit but whose undamped overshoot on the spring (or on the normal springs,
// when the friction torque rocks the block) exceeds it slides at the overshoot, restarts from an
// unloaded spring when the slip reverses, and slides again: it ratchets. A rigid 1 m square on a
// 30° incline with phi = 40°, which should hold, creeps 12 mm in 0.2 s and 52 mm in 1 s (kn = kt =
// 1e7, H = 1 m, dt = 1e-5 s, started at its static normal penetration). Keeping the stretch after
// sliding (the elastic-plastic update of DEM codes) removes the spring reset but not the
// undamped rocking; a contact damping is the remedy, and neither is part of seed 000.
//
// Departures from the paper:
//   * eq. 26, second case, is -kt d_tan without a cap; here a reversal goes back through
//     eq. 25, so |f_t| never exceeds the Coulomb limit even when one step's reversal is
//     larger than limit / kt;
//   * d_tan = 0 has no sliding direction s; the force is then zero and the status stick
//     (there is no tangential motion to resist).
//
// Units: displacements m, forces N per metre of thickness, kt N/m per metre of thickness.

#include "rockcontact/kernel/point.hpp"

namespace rockcontact::contact {

using kernel::Vector2;

struct FrictionLaw {
  double kt = 1.0e7;                // tangential penalty, N/m per metre of thickness, finite > 0
  double friction_angle_deg = 0.0;  // phi, degrees, in [0, 90)
};

inline FrictionLaw default_friction_law() { return {}; }

// Throws std::invalid_argument naming the field when kt is not finite and > 0 or phi is not in
// [0, 90) degrees.
void check_friction_law(const FrictionLaw& law);

// The per-pair record that persists across steps.
struct FrictionState {
  // d: displacement of CP relative to TP at the contact point, m, accumulated since the
  // contact began or since the last sliding step.
  Vector2 displacement;
  // Status found by the last evaluation (true: the force was at the Coulomb limit).
  bool sliding = false;
  // Friction force on CP found by the last evaluation, N/m; on TP it was -force.
  Vector2 force;
};

struct FrictionResult {
  Vector2 force;        // tangential force on CP, N/m; on TP it is -force
  bool sliding = false;  // true when |force| is the Coulomb limit |f_n| tan(phi)
  Vector2 tangential;   // d_tan of eq. 24b, m (the part of d across the normal)
};

// Eq. 24-26 for one pair at one instant. normal_force is the normal force on CP (N/m; only its
// direction and magnitude enter, so its sign convention does not matter). A zero normal force
// gives a zero limit: the pair slides freely. Pure: the state is read, not changed.
FrictionResult evaluate_friction(const FrictionState& state, Vector2 normal_force,
                                 const FrictionLaw& law);

// Stores an evaluation's force and status in the record (done once per instant, after
// evaluate_friction).
void commit_friction(FrictionState& state, const FrictionResult& result);

// §3.2.6: moves d by the step's relative displacement increment Δd (m): d += Δd after a stick
// evaluation, d = Δd after a sliding one.
void advance_friction(FrictionState& state, Vector2 increment);

}  // namespace rockcontact::contact
