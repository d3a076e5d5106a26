#pragma once
// The factor of safety of one block by strength reduction with the implicit 3D DDA (seed 001
// §6.1, eq. 52: FS = tan φ / tan φ_r, φ_r the critical friction angle at which the block starts
// to slide, found by bisection).
//
// Method:
//   1. a trial at the factor F reduces the strength of every contact the block takes part in:
//      each interface and the default law, as they govern a pair that includes the block, get
//      tan φ / F and c / F (the tensile strength, kn and kt stay). Pairs without the block keep
//      their law: the block gets a group of its own, with one interface per group of the other
//      blocks carrying the reduced law that governed that pair;
//   2. each trial runs a fresh Dda3d from the initial state for `time` and judges whether the
//      block slides (below);
//   3. F = max_factor is tried first: a block still standing there is stable_at_max (FS >=
//      max_factor); then F = min_factor: a block sliding there is slides_at_min (FS <
//      min_factor); otherwise [min_factor, max_factor] brackets FS and is bisected at its
//      geometric mean (a relative tolerance halves in log F) until hi / lo - 1 <= tolerance,
//      FS = √(lo hi), the block standing at lo and sliding at hi.
//
// "Slides": the block's centroid moves farther than `slip_ratio` times the block's size,
// measured from where it is at `settle_time`, at some instant up to `time`. The size is the
// cube root of the block's volume: a length that does not depend on the block's orientation or
// elongation the way a bounding-box diagonal does (the §6.1 wedge: 4.43 m, against a 14.8 m
// diagonal), so the threshold stays a fixed fraction of the rigid motion the block can make.
// A trial that has slid stops there.
//
// Why from the settled state: blocks placed exactly on their supports (gap 0, as cut) start
// with unloaded penalty springs and sink into them, by m g / (n kn) normally and the shear's
// share / kt tangentially; under a factor slightly below FS this settling is all the block
// does, and it must not count as sliding. It is far below the threshold for stiff contacts (the
// wedge: ~0.2 mm against 4.4 mm), but a softer law brings it near; measuring from the state at
// settle_time (the springs' period is a few ms for kn ~ 1e10 N/m on 1e5 kg, and the implicit
// step damps it within tens of steps) removes it whatever the stiffness. A block that is
// sliding keeps accelerating after settle_time, so nothing is lost but settle_time of run.
//
// Settling. The penalty springs give way under the block's weight W by about W / (n k), n the
// block's closed constraints at the start and k the softer of kn and kt: the initial
// equilibrium takes the normal part, but a trial whose reduced friction lets the springs
// re-settle tangentially moves the block by up to that much before any sliding. When it reaches
// settling_warning of the slip threshold, a trial can be called sliding for its settling alone
// (kn = 1e9 N/m on a wedge whose FS is 1.55 "slid" both bracket ends, 4.5 mm against 4.48 mm):
// the result carries a warning saying so and what to change.
//
// Contact dashpots. Each trial's contacts carry dashpots of damping ratio `damping_ratio` (or
// the scene's, if larger; dda3d.hpp, "Contact damping"). A block released on penalty springs
// rocks on them; at a small step the implicit integrator hardly damps that (1e-4 s on a wedge
// whose springs ring at ~1 kHz), its contacts open and close, and each opening lets it slip: the
// wedges of a generated family (dynamics/apps/wedge_family.hpp) ratcheted down at factors up to
// 5 % below FS at kn = 1e10 N/m, dt = 1e-4 s, and one heavy wedge at any factor. The dashpots act
// along the normal and, while a contact sticks, along its plane: a block sliding steadily feels
// neither, so they damp the rocking without moving the limit (the same family: within 0.1 % on
// four of five wedges, 1 % on the heavy one, bench/README.md).
//
// Resolution. Just above FS the block slides with an acceleration a ≈ a_0 (1 - FS / F) (a_0 the
// frictionless one, g sin ψ on a plane of dip ψ), so it is called sliding only once
// ½ a (time - settle_time)² exceeds the threshold: the factor found is high by about
//   2 slip_ratio size / (a_0 (time - settle_time)²)            (relative)
// the §6.1 wedge with the defaults: 2 × 4.4e-3 / (4.72 × 0.95²) = 0.21 %. A longer time or a
// smaller slip_ratio lowers it (not below the settling the threshold has to clear).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/dynamics/dda3d.hpp"

namespace rockcontact::dynamics {

struct SafetyFactorParams {
  double time = 1.0;          // s, of each trial, finite > settle_time
  double settle_time = 0.05;  // s, the state the displacement is measured from, finite >= 0
  double slip_ratio = 1.0e-3; // of the block's size (cube root of its volume), in (0, 1)
  double min_factor = 0.1;    // the bracket of the bisection, 0 < min_factor < max_factor
  double max_factor = 10.0;
  double tolerance = 1.0e-3;  // relative width of the final bracket, in (0, 1)
  double damping_ratio = 0.5; // the trials' contact dashpots (header), finite >= 0
};

inline SafetyFactorParams default_safety_factor_params() { return {}; }

// The fraction of the slip threshold the estimated settling may reach before a warning (header).
inline constexpr double settling_warning = 0.1;

enum class SafetyStatus {
  converged,      // min_factor <= FS <= max_factor within tolerance
  stable_at_max,  // the block stands at max_factor: FS >= max_factor (factor_of_safety = it)
  slides_at_min,  // the block slides at min_factor: FS < min_factor (factor_of_safety = it)
};

struct SafetyTrial {
  double factor = 0.0;        // F, dimensionless: tan φ / F, c / F
  bool slid = false;
  double displacement = 0.0;  // m, the centroid's largest from the settled state (up to the stop)
  double run_seconds = 0.0;   // s of wall-clock time the trial took
};

struct SafetyFactorResult {
  double factor_of_safety = 0.0;      // dimensionless (the status says what it bounds)
  // degrees: atan(tan φ / FS) of the first law governing a pair with the block (the first
  // interface in ContactLaw3d::interfaces naming its group, or else the default law).
  double critical_friction_angle_deg = 0.0;
  std::size_t iterations = 0;         // trials run, the two bracket ends included
  SafetyStatus status = SafetyStatus::converged;
  std::vector<SafetyTrial> trials;    // in the order run
  double slip = 0.0;                  // m, the displacement threshold used
  // m: what the block's contacts let it settle, weight / (closed constraints x min(kn, kt)) at
  // the start (header, "Settling"); 0 when it has no closed constraint.
  double settling = 0.0;
  std::vector<std::string> warnings;  // what costs the result accuracy, in words
};

// The factor of safety of the block `block_id` among `blocks` under `law` and `params` (header).
// Throws std::invalid_argument naming the block when it is not among `blocks` or is fixed, or
// naming the field of `safety` out of range; what Dda3d's constructor throws for bad blocks,
// law or params; Stability3dError from a trial that cannot go on.
SafetyFactorResult safety_factor(const std::vector<Block3dSpec>& blocks, const ContactLaw3d& law,
                                 const Dda3dParams& params, const std::string& block_id,
                                 const SafetyFactorParams& safety = default_safety_factor_params());

}  // namespace rockcontact::dynamics
