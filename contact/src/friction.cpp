#include "rockcontact/contact/friction.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rockcontact::contact {
namespace {

double dot(Vector2 a, Vector2 b) { return a.x * b.x + a.y * b.y; }

Vector2 scaled(Vector2 v, double s) { return {v.x * s, v.y * s}; }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// Eq. 25: stick below the limit, slide at it in the direction s = d_tan / |d_tan|.
FrictionResult stick_or_slide(Vector2 d_tan, double kt, double limit) {
  const double length = std::hypot(d_tan.x, d_tan.y);
  FrictionResult out;
  out.tangential = d_tan;
  if (length == 0.0) return out;
  if (kt * length < limit) {
    out.force = scaled(d_tan, -kt);
    return out;
  }
  out.force = scaled(d_tan, -limit / length);
  out.sliding = true;
  return out;
}

}  // namespace

void check_friction_law(const FrictionLaw& law) {
  if (!std::isfinite(law.kt) || !(law.kt > 0.0)) {
    throw std::invalid_argument("friction: kt must be finite and > 0 (N/m), got " +
                                number(law.kt));
  }
  if (!(law.friction_angle_deg >= 0.0 && law.friction_angle_deg < 90.0)) {
    throw std::invalid_argument("friction: friction_angle_deg must be in [0, 90), got " +
                                number(law.friction_angle_deg));
  }
}

FrictionResult evaluate_friction(const FrictionState& state, Vector2 normal_force,
                                 const FrictionLaw& law) {
  const double fn = std::hypot(normal_force.x, normal_force.y);
  const double limit = fn * std::tan(law.friction_angle_deg * (std::numbers::pi / 180.0));
  // Eq. 24: with no normal direction every displacement is tangential.
  Vector2 d_tan = state.displacement;
  if (fn > 0.0) {
    const Vector2 n = scaled(normal_force, 1.0 / fn);
    const double along = dot(state.displacement, n);
    d_tan = {state.displacement.x - along * n.x, state.displacement.y - along * n.y};
  }
  // Eq. 26: still sliding the same way (the last friction force opposes d_tan, which is
  // therefore non-zero).
  if (state.sliding && dot(state.force, d_tan) < 0.0) {
    FrictionResult out;
    out.tangential = d_tan;
    out.force = scaled(d_tan, -limit / std::hypot(d_tan.x, d_tan.y));
    out.sliding = true;
    return out;
  }
  return stick_or_slide(d_tan, law.kt, limit);
}

void commit_friction(FrictionState& state, const FrictionResult& result) {
  state.force = result.force;
  state.sliding = result.sliding;
}

void advance_friction(FrictionState& state, Vector2 increment) {
  if (state.sliding) {
    state.displacement = increment;
  } else {
    state.displacement = {state.displacement.x + increment.x, state.displacement.y + increment.y};
  }
}

}  // namespace rockcontact::contact
