#include "rockcontact/dynamics/apps/wedge_limit_equilibrium.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockcontact::dynamics {
namespace {

using kernel::Point3;

constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

// sin and cos of an angle in degrees, exact at multiples of 90 degrees (as block cutting does),
// so vertical and horizontal joints have exactly axis-aligned normals.
std::pair<double, double> sin_cos_deg(double deg) {
  const double quarter = deg / 90.0;
  if (quarter == std::floor(quarter)) {
    static constexpr double sines[4] = {0, 1, 0, -1};
    const auto q = static_cast<int>(std::fmod(std::fmod(quarter, 4.0) + 4.0, 4.0));
    return {sines[q], sines[(q + 1) % 4]};
  }
  const double rad = deg / degrees_per_radian;
  return {std::sin(rad), std::cos(rad)};
}

double dot(const Point3& u, const Point3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }

Point3 cross(const Point3& u, const Point3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}

Point3 scaled(const Point3& u, double k) { return {u.x * k, u.y * k, u.z * k}; }

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

[[noreturn]] void refuse(const std::string& field, const std::string& expected, double got) {
  throw std::invalid_argument(field + ": expected " + expected + ", got " + number_text(got));
}

void check_joint(const WedgeJoint& joint, const std::string& name) {
  if (!(joint.dip_deg >= 0 && joint.dip_deg <= 90)) {
    refuse(name + ".dip_deg", "degrees in [0, 90]", joint.dip_deg);
  }
  if (!(joint.dip_direction_deg >= 0 && joint.dip_direction_deg < 360)) {
    refuse(name + ".dip_direction_deg", "degrees in [0, 360) clockwise from North", joint.dip_direction_deg);
  }
  if (!(joint.friction_angle_deg >= 0 && joint.friction_angle_deg < 90)) {
    refuse(name + ".friction_angle_deg", "degrees in [0, 90)", joint.friction_angle_deg);
  }
  if (!(std::isfinite(joint.cohesion_pa) && joint.cohesion_pa >= 0)) {
    refuse(name + ".cohesion_pa", "a finite number of Pa >= 0", joint.cohesion_pa);
  }
  if (!(std::isfinite(joint.area) && joint.area >= 0)) {
    refuse(name + ".area", "a finite number of m² >= 0", joint.area);
  }
}

Point3 upward_normal(const WedgeJoint& joint) {
  const auto [sin_dip, cos_dip] = sin_cos_deg(joint.dip_deg);
  const auto [sin_dir, cos_dir] = sin_cos_deg(joint.dip_direction_deg);
  return {sin_dip * sin_dir, sin_dip * cos_dir, cos_dip};
}

Point3 dip_vector(const WedgeJoint& joint) {
  const auto [sin_dip, cos_dip] = sin_cos_deg(joint.dip_deg);
  const auto [sin_dir, cos_dir] = sin_cos_deg(joint.dip_direction_deg);
  return {cos_dip * sin_dir, cos_dip * cos_dir, -sin_dip};
}

double tan_deg(double deg) { return std::tan(deg / degrees_per_radian); }

// The azimuth of a direction's horizontal part, degrees in [0, 360); 0 for a vertical one
// (whose signed zeros would make atan2 answer ±180).
double trend_deg(const Point3& direction) {
  if (direction.x == 0 && direction.y == 0) return 0.0;
  const double trend = std::atan2(direction.x, direction.y) * degrees_per_radian;
  if (trend > 0) return trend;
  const double turned = trend + 360.0;
  return turned < 360.0 ? turned : 0.0;  // −0 and tiny negative angles round to 360
}

// Fills the line of intersection, its plunge and trend; refuses parallel planes and a line
// that does not plunge. Returns sin θ = |n_A × n_B|.
double intersect(WedgeLimitEquilibrium& r) {
  const Point3 c = cross(r.normal_a, r.normal_b);
  const double sin_theta = std::sqrt(dot(c, c));
  if (!(sin_theta >= wedge_parallel_sine)) {
    throw std::invalid_argument(
        "joint_a, joint_b: expected planes that intersect, got parallel planes (sine of the angle between "
        "their normals " + number_text(sin_theta) + ")");
  }
  r.intersection = scaled(c, (c.z > 0 ? -1.0 : 1.0) / sin_theta);
  if (!(-r.intersection.z >= wedge_plunge_sine)) {
    throw std::invalid_argument(
        "joint_a, joint_b: expected a line of intersection that plunges, got a horizontal one (trend " +
        number_text(trend_deg(r.intersection)) +
        " degrees): the weight has no component along it");
  }
  r.plunge_deg = std::asin(-r.intersection.z) * degrees_per_radian;
  r.trend_deg = trend_deg(r.intersection);
  return sin_theta;
}

// Sliding on one plane alone, down its dip vector: N = W cos ψ, D = W sin ψ.
void slide_on_plane(WedgeLimitEquilibrium& r, const WedgeJoint& joint, double weight_n, double& coefficient,
                    double& reaction) {
  const auto [sin_dip, cos_dip] = sin_cos_deg(joint.dip_deg);
  r.sliding = dip_vector(joint);
  r.driving_force = weight_n * sin_dip;
  coefficient = cos_dip / sin_dip;
  reaction = weight_n * cos_dip;
  r.factor_of_safety =
      coefficient * tan_deg(joint.friction_angle_deg) + joint.cohesion_pa * joint.area / r.driving_force;
}

}  // namespace

std::string_view to_string(WedgeMode mode) {
  switch (mode) {
    case WedgeMode::wedge: return "wedge";
    case WedgeMode::plane_a: return "plane_a";
    case WedgeMode::plane_b: return "plane_b";
    case WedgeMode::lift_off: return "lift_off";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& out, WedgeMode mode) { return out << to_string(mode); }

WedgeLimitEquilibrium wedge_factor_of_safety(const WedgeJoint& a, const WedgeJoint& b, double weight_n) {
  check_joint(a, "joint_a");
  check_joint(b, "joint_b");
  if (!(std::isfinite(weight_n) && weight_n > 0)) refuse("weight_n", "a finite number of N > 0", weight_n);

  WedgeLimitEquilibrium r;
  r.normal_a = upward_normal(a);
  r.normal_b = upward_normal(b);
  const double sin_theta = intersect(r);
  // 1 − m² = |n_A × n_B|² (Lagrange's identity), without the cancellation of 1 − m² near m = ±1.
  const double m = dot(r.normal_a, r.normal_b);
  const double one_minus_m2 = sin_theta * sin_theta;
  const double sin_plunge = -r.intersection.z;
  const double coefficient_a = (r.normal_a.z - m * r.normal_b.z) / (one_minus_m2 * sin_plunge);
  const double coefficient_b = (r.normal_b.z - m * r.normal_a.z) / (one_minus_m2 * sin_plunge);

  if (coefficient_a <= 0 && coefficient_b <= 0) {
    r.mode = WedgeMode::lift_off;
    r.sliding = r.intersection;
    r.driving_force = weight_n * sin_plunge;
    return r;
  }
  if (coefficient_b <= 0) {
    r.mode = WedgeMode::plane_a;
    slide_on_plane(r, a, weight_n, r.coefficient_a, r.normal_reaction_a);
    return r;
  }
  if (coefficient_a <= 0) {
    r.mode = WedgeMode::plane_b;
    slide_on_plane(r, b, weight_n, r.coefficient_b, r.normal_reaction_b);
    return r;
  }
  r.mode = WedgeMode::wedge;
  r.sliding = r.intersection;
  r.coefficient_a = coefficient_a;
  r.coefficient_b = coefficient_b;
  r.normal_reaction_a = weight_n * (r.normal_a.z - m * r.normal_b.z) / one_minus_m2;
  r.normal_reaction_b = weight_n * (r.normal_b.z - m * r.normal_a.z) / one_minus_m2;
  r.driving_force = weight_n * sin_plunge;
  const double cohesion = a.cohesion_pa * a.area + b.cohesion_pa * b.area;
  r.factor_of_safety = coefficient_a * tan_deg(a.friction_angle_deg) + coefficient_b * tan_deg(b.friction_angle_deg) +
                       cohesion / r.driving_force;
  return r;
}

}  // namespace rockcontact::dynamics
