#pragma once
// Coulomb friction of a 2D contact pair from the relative displacement of its contact point,
// under one of two laws (FrictionModel). Both keep one FrictionState per pair from the step the
// pair starts overlapping (stick, nothing stretched) until it separates (the record is then
// dropped), and both cap the tangential force at
//   limit = |f_n| tan(phi) + c L
// with f_n the normal force on CP, phi the friction angle, c the cohesion (Pa) and L the
// contact length (m; half the perimeter of the intersection polygon, which is the length of a
// thin face-to-face overlap). The force acts on CP at the contact point pg and its negative on TP.
// Between t_n and t_n+1 the relative displacement increment Δd = Δu_CP(pg) - Δu_TP(pg) moves the
// record (advance_friction, seed 000 §3.2.6).
//
// ## elastoplastic (the default)
// A persistent tangential spring on the accumulated relative tangential displacement δ_t, the
// elastic-perfectly-plastic return mapping of DEM codes. The record holds δ_t as a vector along
// the tangent t = (-n_y, n_x) of the unit normal n of its last evaluation, and the step's
// increments are added to it. At t_n, with the new normal n':
//   s     = δ · t                 the tangential stretch in the frame it was built in (the normal
//                                 part of the increments is dropped);
//   δ_t   = s t'                  the stretch turned with the contact frame (t' = perp(n'): a
//                                 rotation, so |δ_t| = |s| is kept);
//   f_t   = -kt δ_t               if kt |s| <= limit                          (stick)
//   f_t   = -limit δ_t / |δ_t|,   δ_t <- -f_t / kt   otherwise                 (plastic slip)
// The stretch is held at the cap while the contact slides and is never reset, so a block that
// rebounds unloads the spring from the cap instead of from zero: a load below the limit cannot
// ratchet the block. A slip from the stretch s_0 kept at the last evaluation to the capped s_c
// dissipates ½ kt (s_0 + s_c)(s - s_c): the friction force's work over the step by the trapezoid
// rule (as the integrator counts contact work) less the change of the spring's energy; while the
// pair keeps sliding (s_0 = s_c) it is limit × the plastic slip |s - s_c|
// (FrictionResult::dissipated).
//
// ## paper (seed 000 §3.2.5-§3.2.6, eq. 24-26)
// At t_n, with n = f_n / |f_n|:
//   d_nor = (d . n) n,  d_tan = d - d_nor,  s = d_tan / |d_tan|                      (eq. 24)
//   stick at t_n-1:  f_t = -kt d_tan           if kt |d_tan| <  limit                (eq. 25)
//                    f_t = -limit s            if kt |d_tan| >= limit
//   slide at t_n-1:  f_t = -limit s            if f_t(n-1) . d_tan <  0              (eq. 26)
//                    otherwise the motion has reversed against the last friction force
//                    and eq. 25 decides again
// and §3.2.6: d += Δd after a stick evaluation, d = Δd after a sliding one (the spring restarts
// from the current position). Kept as the paper has it, for the paper's scenes. Its known
// behaviour: the reset after a sliding step forgets the spring's stretch, so a pair whose load
// stays below the limit but whose undamped overshoot exceeds it slides at the overshoot,
// restarts from an unloaded spring when the slip reverses, and slides again: it ratchets (a
// 10 m block on a 40° slope with phi = 42° slid 411 mm in 1 s). Departures from the paper:
//   * eq. 26, second case, is -kt d_tan without a cap; here a reversal goes back through
//     eq. 25, so |f_t| never exceeds the limit even when one step's reversal is larger than
//     limit / kt;
//   * d_tan = 0 has no sliding direction s; the force is then zero and the status stick.
//   * the limit includes c L (zero unless the scene sets a cohesion).
//
// Units: displacements m, forces N per metre of thickness, kt N/m per metre of thickness,
// cohesion Pa (N/m² times L in m gives N per metre of thickness).

#include <optional>
#include <string_view>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::contact {

using kernel::Vector2;

enum class FrictionModel { elastoplastic, paper };

// "elastoplastic" or "paper"; nothing otherwise.
std::optional<FrictionModel> parse_friction_model(std::string_view text);

struct FrictionLaw {
  double kt = 1.0e7;                // tangential penalty, N/m per metre of thickness, finite > 0
  double friction_angle_deg = 0.0;  // phi, degrees, in [0, 90)
  double cohesion = 0.0;            // c, Pa, finite >= 0
  FrictionModel model = FrictionModel::elastoplastic;
};

inline FrictionLaw default_friction_law() { return {}; }

// Throws std::invalid_argument naming the field when kt is not finite and > 0, phi is not in
// [0, 90) degrees or the cohesion is not finite and >= 0.
void check_friction_law(const FrictionLaw& law);

// The per-pair record that persists across steps.
struct FrictionState {
  // paper: d, the displacement of CP relative to TP at the contact point, m, accumulated since
  // the contact began or since the last sliding step. elastoplastic: the spring's stretch δ_t
  // along the tangent of `normal`, plus the increments added since that evaluation.
  Vector2 displacement;
  // Status found by the last evaluation (true: the force was at the limit).
  bool sliding = false;
  // Friction force on CP found by the last evaluation, N/m; on TP it was -force.
  Vector2 force;
  // elastoplastic: the unit normal on CP of the last evaluation (zero before the first).
  Vector2 normal{};
};

struct FrictionResult {
  Vector2 force;         // tangential force on CP, N/m; on TP it is -force
  bool sliding = false;  // true when |force| is the limit |f_n| tan(phi) + c L
  Vector2 tangential;    // paper: d_tan of eq. 24b; elastoplastic: the stretch δ_t kept, m
  double dissipated = 0.0;  // elastoplastic: the energy the slip dissipated (above), J/m
  FrictionState next;       // the record after this evaluation (commit_friction stores it)
};

// Whether the limit applies: `locked` holds every contact in stick whatever its load (the
// tangential springs of a static pre-solve, dynamics/dda2d.hpp).
enum class Slip { allowed, locked };

// One pair at one instant. normal_force is the normal force on CP (N/m; only its direction and
// magnitude enter). contact_length is L of the cohesion term, m (>= 0). A zero normal force and
// no cohesion give a zero limit: the pair slides freely. Pure: the state is read, not changed.
FrictionResult evaluate_friction(const FrictionState& state, Vector2 normal_force,
                                 const FrictionLaw& law, double contact_length = 0.0,
                                 Slip slip = Slip::allowed);

// Stores an evaluation in the record (done once per instant, after evaluate_friction).
void commit_friction(FrictionState& state, const FrictionResult& result);

// §3.2.6: moves the record by the step's relative displacement increment Δd (m): d += Δd, except
// that the paper's law restarts from d = Δd after a sliding evaluation.
void advance_friction(FrictionState& state, Vector2 increment, const FrictionLaw& law);

}  // namespace rockcontact::contact
