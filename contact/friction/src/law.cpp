#include "rockcontact/contact/friction/law.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
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

double limit_of(const FrictionLaw& law, double normal, double contact_length) {
  return normal * std::tan(law.friction_angle_deg * (std::numbers::pi / 180.0)) +
         law.cohesion * contact_length;
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

FrictionResult paper_friction(const FrictionState& state, Vector2 normal_force, double limit,
                              double kt) {
  const double fn = std::hypot(normal_force.x, normal_force.y);
  // Eq. 24: with no normal direction every displacement is tangential.
  Vector2 d_tan = state.displacement;
  if (fn > 0.0) {
    const Vector2 n = scaled(normal_force, 1.0 / fn);
    const double along = dot(state.displacement, n);
    d_tan = {state.displacement.x - along * n.x, state.displacement.y - along * n.y};
  }
  FrictionResult out;
  // Eq. 26: still sliding the same way (the last friction force opposes d_tan, which is
  // therefore non-zero).
  if (state.sliding && dot(state.force, d_tan) < 0.0) {
    out.tangential = d_tan;
    out.force = scaled(d_tan, -limit / std::hypot(d_tan.x, d_tan.y));
    out.sliding = true;
  } else {
    out = stick_or_slide(d_tan, kt, limit);
  }
  out.next = state;  // d itself moves only in advance_friction
  return out;
}

FrictionResult elastoplastic_friction(const FrictionState& state, Vector2 normal_force,
                                      double limit, double kt) {
  const double fn = std::hypot(normal_force.x, normal_force.y);
  const Vector2 normal = fn > 0.0 ? scaled(normal_force, 1.0 / fn) : state.normal;
  // The frame the stretch was built in: that of the last evaluation, or this one at the start.
  const Vector2 built_in = state.normal.x == 0.0 && state.normal.y == 0.0 ? normal : state.normal;
  const Vector2 tangent{-normal.y, normal.x};
  const Vector2 built_tangent{-built_in.y, built_in.x};
  const double s = dot(state.displacement, built_tangent);
  FrictionResult out;
  const double cap = limit / kt;  // the largest stretch the limit allows, m
  double kept = s;
  if (std::fabs(s) > cap) {
    kept = std::copysign(cap, s);
    out.sliding = true;
    const double previous = -dot(state.force, built_tangent) / kt;  // the stretch it last kept
    out.dissipated = 0.5 * kt * (previous + kept) * (s - kept);
  }
  out.tangential = scaled(tangent, kept);
  out.force = scaled(out.tangential, -kt);
  out.next = {out.tangential, out.sliding, out.force, normal};
  return out;
}

}  // namespace

std::optional<FrictionModel> parse_friction_model(std::string_view text) {
  if (text == "elastoplastic") return FrictionModel::elastoplastic;
  if (text == "paper") return FrictionModel::paper;
  return std::nullopt;
}

void check_friction_law(const FrictionLaw& law) {
  if (!std::isfinite(law.kt) || !(law.kt > 0.0)) {
    throw std::invalid_argument("friction: kt must be finite and > 0 (N/m), got " +
                                number(law.kt));
  }
  if (!(law.friction_angle_deg >= 0.0 && law.friction_angle_deg < 90.0)) {
    throw std::invalid_argument("friction: friction_angle_deg must be in [0, 90), got " +
                                number(law.friction_angle_deg));
  }
  if (!std::isfinite(law.cohesion) || !(law.cohesion >= 0.0)) {
    throw std::invalid_argument("friction: cohesion must be finite and >= 0 (Pa), got " +
                                number(law.cohesion));
  }
}

FrictionResult evaluate_friction(const FrictionState& state, Vector2 normal_force,
                                 const FrictionLaw& law, double contact_length, Slip slip) {
  const double fn = std::hypot(normal_force.x, normal_force.y);
  const double limit = slip == Slip::locked ? std::numeric_limits<double>::infinity()
                                            : limit_of(law, fn, contact_length);
  FrictionResult out = law.model == FrictionModel::paper
                           ? paper_friction(state, normal_force, limit, law.kt)
                           : elastoplastic_friction(state, normal_force, limit, law.kt);
  out.next.force = out.force;
  out.next.sliding = out.sliding;
  return out;
}

void commit_friction(FrictionState& state, const FrictionResult& result) { state = result.next; }

void advance_friction(FrictionState& state, Vector2 increment, const FrictionLaw& law) {
  if (law.model == FrictionModel::paper && state.sliding) {
    state.displacement = increment;
  } else {
    state.displacement = {state.displacement.x + increment.x, state.displacement.y + increment.y};
  }
}

}  // namespace rockcontact::contact
