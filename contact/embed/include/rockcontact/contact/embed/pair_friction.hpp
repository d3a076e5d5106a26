#pragma once
// Coulomb friction for host codes, on top of the pair API (pair_contact.hpp): the tangential
// force of a contacting pair from the relative motion of its contact point, with the per-pair
// history kept by the host as a small value.
//
//   rockcontact::PairFrictionParams friction = rockcontact::default_pair_friction_params();
//   friction.friction_angle_deg = 30.0;
//   std::map<std::pair<int, int>, rockcontact::PairFrictionState> states;  // the host's choice
//   each step, for each candidate pair (a, b):
//     const rockcontact::PairContact c = contact.evaluate(a_xy, a_pose, b_xy, b_pose);
//     if (!c.has_point) { states.erase({a, b}); continue; }
//     const rockcontact::PairFriction t =
//         rockcontact::evaluate_pair_friction(states[{a, b}], c, increment, friction);
//     apply c.force + t.force to a at c.point, and their negative to b at c.point;
//
// The law is contact::evaluate_friction (friction.hpp; read it for the two models, the
// elastoplastic return mapping being the default), called as the explicit DDA calls it at each
// evaluation (dynamics/dda2d/src/dda2d.cpp): the record moves by the step's relative displacement
// increment Δd of the contact point (contact::advance_friction), is evaluated with the new
// normal force and contact length, and the evaluation is stored. The tangential force is capped
// at the Coulomb limit
//   |f_n| tan(phi) + c L
// with f_n = c.force, L = c.length (half the perimeter of the intersection polygon) and c the
// cohesion.
//
// The increment: Δd = Δu_a(p) - Δu_b(p), the displacement since the previous call of the
// material point of a at the previous contact point p minus that of b at the same point (m,
// world frame). A host that integrates velocities may take (v_a(p) - v_b(p)) Δt with
// v(p) = v + ω × (p - centroid) of each block. Its normal part does not matter: only the part
// along the contact's tangent stretches the spring.
//
// The lifetime of a state (one per contacting pair, and per pair of convex parts when blocks are
// split): a default-constructed PairFrictionState is a new contact, in stick with nothing
// stretched. The call that first finds the pair in contact ignores its increment (the spring is
// anchored where the blocks first overlap). A call on a pair that is not in contact
// (c.has_point false) resets the state to a new contact and returns no force: the host may drop
// its stored state then, which is the same thing. Keep one state per ordered pair: swapping a
// and b flips the sign of the force, the normal and the increment.
//
// Units: SI per metre of thickness (2D): kt N/m per metre of thickness (N/m²), cohesion Pa,
// forces N/m, dissipated energy J/m.

#include <array>

#include "rockcontact/contact/friction/law.hpp"
#include "rockcontact/contact/embed/pair_contact.hpp"

namespace rockcontact {

struct PairFrictionParams {
  double kt = 1.0e7;                // tangential penalty, N/m per metre of thickness, finite > 0
  double friction_angle_deg = 0.0;  // phi, degrees, in [0, 90)
  double cohesion = 0.0;            // c, Pa, finite >= 0
  contact::FrictionModel model = contact::FrictionModel::elastoplastic;
};

// kt = 1e7 N/m², phi = 0 (frictionless), no cohesion, the elastoplastic law.
PairFrictionParams default_pair_friction_params();

// Throws std::invalid_argument naming the field ("kt", "friction_angle_deg", "cohesion") and its
// allowed range when kt is not finite and > 0, phi is not in [0, 90) degrees or the cohesion is
// not finite and >= 0.
void check_pair_friction_params(const PairFrictionParams& params);

// The friction history of one contacting pair, kept by the host between calls. A plain value:
// copy it, store it in any container; the default is a new contact. Its fields are those of
// the law's record (friction.hpp) and are read and written by evaluate_pair_friction only.
struct PairFrictionState {
  contact::FrictionState record;  // the law's record (stretch, last force, normal, status)
  bool in_contact = false;        // true once a call has found the pair in contact
};

// The tangential force of one evaluation.
struct PairFriction {
  double force[2] = {0.0, 0.0};  // tangential (friction) force on a, N/m, world frame, acting
                                 // at the contact point c.point; on b it is -force
  bool sliding = false;          // true when |force| is at the Coulomb limit
  double dissipated = 0.0;       // energy the slip dissipated since the previous call, J/m:
                                 // elastoplastic: limit × plastic slip while sliding (friction.hpp);
                                 // paper: the previous force's magnitude × the tangential part of
                                 // the increment when the previous call slid, as the DDA counts it
};

// Advances `state` by `increment` (Δd above, m, world frame), evaluates the friction of the
// contact `c` just returned by PairEvaluator::evaluate, stores the evaluation in `state` and
// returns it. When c.has_point is false the state is reset and the result is zero.
// Throws std::invalid_argument, leaving the state unchanged, when the params are invalid (see
// check_pair_friction_params), the increment is not finite, or c has a non-finite force or a
// contact length that is not finite and >= 0.
PairFriction evaluate_pair_friction(PairFrictionState& state, const PairContact& c,
                                    std::array<double, 2> increment,
                                    const PairFrictionParams& params);

}  // namespace rockcontact
