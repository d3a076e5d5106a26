// A DEM-style host of rockcontact with friction. The host owns the bodies, the time loop and the
// damping; each step it asks the library for the normal force of a pair (pair_contact.hpp) and
// for its friction force (pair_friction.hpp), keeping the pair's friction state between steps.
// A 1 m square block is released at rest on a 30° slope with a friction angle of 20° and slides
// down; its runout after 2 s is checked against the rigid-block solution
//   s(t) = ½ g (sin θ - cos θ tan φ) t².
// Units are SI per metre of thickness (2D): forces N/m, masses kg/m.
//
// Build it against an installed rockcontact, with the CMakeLists.txt beside it or with
//   g++ sliding_host.cpp $(pkg-config --static --cflags --libs rockcontact)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <rockcontact/contact/embed/pair_friction.hpp>
#include <rockcontact/version.hpp>

namespace {

// Vertices about each block's centroid, counter-clockwise: a pose is the centroid and rotation.
constexpr double block_xy[] = {-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5};    // 1 m x 1 m
constexpr double slope_xy[] = {-5.0, -0.5, 5.0, -0.5, 5.0, 0.5, -5.0, 0.5};    // 10 m x 1 m

struct Body {
  double m = 0.0;             // kg/m
  double I = 0.0;             // kg m, about the centroid
  rockcontact::Pose2 pose;    // centroid (m) and rotation (rad)
  double vx = 0.0, vy = 0.0;  // m/s
  double w = 0.0;             // rad/s
};

// Where a material point of a body that was at `point` under pose `from` is under pose `to`.
void carry(const rockcontact::Pose2& from, const rockcontact::Pose2& to, const double (&point)[2],
           double (&out)[2]) {
  const double turn = to.theta - from.theta, c = std::cos(turn), s = std::sin(turn);
  const double rx = point[0] - from.x, ry = point[1] - from.y;
  out[0] = to.x + c * rx - s * ry;
  out[1] = to.y + s * rx + c * ry;
}

}  // namespace

int main() {
  constexpr double L = 1.0;          // block width (and height), m
  constexpr double rho = 2000.0;     // kg/m³
  constexpr double g = 9.81;         // m/s²
  constexpr double zeta = 0.5;       // damping ratio of the normal dashpot
  constexpr double duration = 2.0;   // s
  const double theta = 30.0 * std::numbers::pi / 180.0;  // slope angle
  constexpr double phi_deg = 20.0;                        // friction angle, < 30°: it slides

  rockcontact::PairContactParams params = rockcontact::default_pair_contact_params();
  params.kn = 1.0e9;  // Pa
  params.H = 1.0;     // m
  rockcontact::PairEvaluator contact(params);
  rockcontact::PairFrictionParams friction = rockcontact::default_pair_friction_params();
  friction.kt = 1.0e9;  // N/m per metre of thickness
  friction.friction_angle_deg = phi_deg;
  rockcontact::PairFrictionState state;  // the only pair's friction history, kept by the host

  // The slope descends along e = (cos θ, -sin θ); n = (sin θ, cos θ) is its outward normal.
  const double ex = std::cos(theta), ey = -std::sin(theta);
  const double nx = std::sin(theta), ny = std::cos(theta);
  const rockcontact::Pose2 slope_pose{0.0, 0.0, -theta};  // fixed: top face through 0.5 n

  Body block;
  block.m = rho * L * L;
  block.I = block.m * (L * L + L * L) / 12.0;
  // Released at rest 3 m up the slope, pressed to the static depth of its weight's normal part,
  // F = kn (2 L δ - δ²) / H = m g cos θ (dem_host.cpp derives F), so that the normal direction
  // starts in balance.
  const double depth = L - std::sqrt(L * L - block.m * g * std::cos(theta) * params.H / params.kn);
  const double up = 0.5 + 0.5 * L - depth;
  block.pose = {-3.0 * ex + up * nx, -3.0 * ey + up * ny, -theta};
  const rockcontact::Pose2 start = block.pose;

  // Normal stiffness of the face 2 kn L / H = 2e9 N/m² on 2000 kg/m: omega = 1000 rad/s; the
  // tangential spring kt: omega = 707 rad/s. Semi-implicit Euler is stable for omega dt < 2
  // (less with the dashpot, 2 (sqrt(1 + zeta²) - zeta) = 1.24); dt = 1e-5 s gives omega dt = 0.01.
  const double k = 2.0 * params.kn * L / params.H;
  const double c = 2.0 * zeta * std::sqrt(k * block.m);  // N s/m², along the contact normal
  constexpr double dt = 1.0e-5;
  const long steps = std::lround(duration / dt);

  rockcontact::Pose2 last_pose = block.pose;  // the pose at the previous evaluation
  double last_point[2] = {0.0, 0.0};          // the contact point then (when in contact)
  double dissipated = 0.0;                    // J/m, by the slip
  double friction_force[2] = {0.0, 0.0};      // N/m, on the block, at the last step
  for (long step = 0; step < steps; ++step) {
    double fx = 0.0, fy = -block.m * g, torque = 0.0;
    const rockcontact::PairContact r = contact.evaluate(block_xy, block.pose, slope_xy, slope_pose);
    // The friction law needs the displacement of the block's material point at the last contact
    // point since the last evaluation (the slope does not move); on a new contact it is ignored.
    double moved[2];
    carry(last_pose, block.pose, last_point, moved);
    const rockcontact::PairFriction t = rockcontact::evaluate_pair_friction(
        state, r, {moved[0] - last_point[0], moved[1] - last_point[1]}, friction);
    dissipated += t.dissipated;
    friction_force[0] = t.force[0];
    friction_force[1] = t.force[1];
    if (r.has_point) {
      const double f = std::hypot(r.force[0], r.force[1]);
      const double ux = r.force[0] / f, uy = r.force[1] / f;
      const double rx = r.point[0] - block.pose.x, ry = r.point[1] - block.pose.y;
      const double vn = (block.vx - block.w * ry) * ux + (block.vy + block.w * rx) * uy;
      const double fn = std::max(0.0, f - c * vn);  // elastic force plus the host's dashpot
      const double px = fn * ux + t.force[0], py = fn * uy + t.force[1];
      fx += px;
      fy += py;
      torque += rx * py - ry * px;
      last_point[0] = r.point[0];
      last_point[1] = r.point[1];
    }
    last_pose = block.pose;
    block.vx += dt * fx / block.m;
    block.vy += dt * fy / block.m;
    block.w += dt * torque / block.I;
    block.pose.x += dt * block.vx;
    block.pose.y += dt * block.vy;
    block.pose.theta += dt * block.w;
  }

  const double tan_phi = std::tan(phi_deg * std::numbers::pi / 180.0);
  const double a = g * (std::sin(theta) - std::cos(theta) * tan_phi);
  const double expected = 0.5 * a * duration * duration;
  const double runout = (block.pose.x - start.x) * ex + (block.pose.y - start.y) * ey;
  const double runout_err = std::abs(runout - expected) / expected;
  // The slip dissipates the Coulomb limit m g cos θ tan φ times the distance slid.
  const double expected_dissipated = block.m * g * std::cos(theta) * tan_phi * expected;
  const double dissipated_err = std::abs(dissipated - expected_dissipated) / expected_dissipated;
  // The rigid solution has the friction at its limit from t = 0; here the spring starts
  // unstretched, s'' = g sin θ - (kt / m) s, and reaches its cap limit / kt = 6.2 µm when
  // 1 - cos(ω t1) = tan φ / tan θ (ω = 707 rad/s: t1 = 1.7 ms) at a speed 3.4 mm/s above the
  // rigid block's, which carries it 6.8 mm (0.19 %) further in 2 s. The normal contact's own
  // start-up (the friction's moment rocks the block by ~2e-5 rad) adds a little: measured 0.25 %,
  // 0.15 % with kt ten times stiffer, 0.21 % with kn ten times stiffer. 1 % bounds that start-up
  // with a margin and still catches a friction force off by 1 % of its limit (which moves the
  // runout by 1.7 %). The dissipation carries the same start-up error.
  const bool ok = runout_err <= 0.01 && dissipated_err <= 0.01;

  std::printf("rockcontact %s: %ld steps of %.3g s, block on a %.0f deg slope, phi = %.0f deg\n",
              ROCKCONTACT_VERSION_STRING, steps, dt, theta * 180.0 / std::numbers::pi, phi_deg);
  std::printf("runout %.6f m, rigid 1/2 g (sin t - cos t tan phi) t^2 = %.6f m, relative error %.2e "
              "(<= 1e-2)\n", runout, expected, runout_err);
  std::printf("dissipated %.6e J/m, m g cos t tan phi s = %.6e J/m, relative error %.2e (<= 1e-2)\n",
              dissipated, expected_dissipated, dissipated_err);
  std::printf("rotation %.3g rad, last friction force (%.6e, %.6e) N/m, %s\n",
              block.pose.theta + theta, friction_force[0], friction_force[1],
              state.record.sliding ? "sliding" : "stick");
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
