#include "rockcontact/contact/embed/pair_friction.hpp"

#include <cmath>
#include <stdexcept>

namespace rockcontact {
namespace {

contact::FrictionLaw law_of(const PairFrictionParams& p) {
  return {p.kt, p.friction_angle_deg, p.cohesion, p.model};
}

void check_input(const PairContact& c, std::array<double, 2> increment) {
  if (!std::isfinite(increment[0]) || !std::isfinite(increment[1])) {
    throw std::invalid_argument("friction: the increment must be finite (m)");
  }
  if (!std::isfinite(c.force[0]) || !std::isfinite(c.force[1])) {
    throw std::invalid_argument("friction: the contact's force must be finite (N/m)");
  }
  if (!std::isfinite(c.length) || !(c.length >= 0.0)) {
    throw std::invalid_argument("friction: the contact's length must be finite and >= 0 (m)");
  }
}

// The paper's law counts no dissipation in its evaluation: a pair that slid at the previous
// call dissipates that force's magnitude times the tangential slip of this increment (the force
// is tangential, so in 2D that is |f · Δd|), as the DDA counts it.
double paper_dissipation(const contact::FrictionState& previous, contact::Vector2 increment) {
  if (!previous.sliding) return 0.0;
  return std::fabs(previous.force.x * increment.x + previous.force.y * increment.y);
}

}  // namespace

PairFrictionParams default_pair_friction_params() { return {}; }

void check_pair_friction_params(const PairFrictionParams& params) {
  contact::check_friction_law(law_of(params));
}

PairFriction evaluate_pair_friction(PairFrictionState& state, const PairContact& c,
                                    std::array<double, 2> increment,
                                    const PairFrictionParams& params) {
  const contact::FrictionLaw law = law_of(params);
  contact::check_friction_law(law);
  check_input(c, increment);
  PairFriction out;
  if (!c.has_point) {
    state = {};
    return out;
  }
  contact::FrictionState record = state.record;
  double dissipated = 0.0;
  if (state.in_contact) {
    const contact::Vector2 d{increment[0], increment[1]};
    if (law.model == contact::FrictionModel::paper) dissipated = paper_dissipation(record, d);
    contact::advance_friction(record, d, law);
  }
  const contact::FrictionResult r =
      contact::evaluate_friction(record, {c.force[0], c.force[1]}, law, c.length);
  contact::commit_friction(record, r);
  state = {record, true};
  out.force[0] = r.force.x;
  out.force[1] = r.force.y;
  out.sliding = r.sliding;
  out.dissipated = law.model == contact::FrictionModel::paper ? dissipated : r.dissipated;
  return out;
}

}  // namespace rockcontact
