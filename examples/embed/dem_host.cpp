// A DEM-style host of rockcontact. The host owns the bodies, the time loop and the damping; each
// step it asks the library for one thing per pair: the normal force of the potential contact
// law (seed 000 eq. 11-20) and the point it acts at. A 1 m square block is dropped 1 cm onto a
// fixed 4 m x 1 m base, settles, and its resting state is checked against the law's static
// solution. Units are SI per metre of thickness (2D): forces N/m, masses kg/m.
//
// Build it against an installed rockcontact, with the CMakeLists.txt beside it or with
//   g++ dem_host.cpp $(pkg-config --static --cflags --libs rockcontact)
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <rockcontact/contact/embed/pair_contact.hpp>
#include <rockcontact/version.hpp>

namespace {

// Vertices in each block's own frame, counter-clockwise, about its centroid, so that a pose is
// the centroid's position and rotation: the host's body state is the library's input.
constexpr double block_xy[] = {-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5};  // 1 m x 1 m
constexpr double base_xy[] = {-2.0, -0.5, 2.0, -0.5, 2.0, 0.5, -2.0, 0.5};   // 4 m x 1 m

struct Body {
  double m = 0.0;             // kg/m
  double I = 0.0;             // kg m, about the centroid
  rockcontact::Pose2 pose;    // centroid (m) and rotation (rad)
  double vx = 0.0, vy = 0.0;  // m/s
  double w = 0.0;             // rad/s
};

}  // namespace

int main() {
  constexpr double L = 1.0;        // block width (and height), m
  constexpr double rho = 2000.0;   // kg/m³
  constexpr double g = 9.81;       // m/s²
  constexpr double zeta = 0.5;     // damping ratio of the contact dashpot
  constexpr double duration = 1.0; // s: the fall takes 0.045 s, the rest is settling

  rockcontact::PairContactParams params = rockcontact::default_pair_contact_params();
  params.kn = 1.0e8;  // Pa
  params.H = 1.0;     // m
  rockcontact::PairEvaluator contact(params);  // one per thread; reused every step

  Body block;
  block.m = rho * L * L;
  block.I = block.m * (L * L + L * L) / 12.0;
  block.pose = {0.0, 0.5 + 0.5 * L + 0.01, 0.0};  // bottom 1 cm above the base's top (y = 0.5)
  const rockcontact::Pose2 base_pose{};          // fixed: the host never moves it

  // For a flat face of width L pressed to depth d, the law gives F = kn (2 L d - d²) / H (see
  // the check below), so the contact is a spring of stiffness k = 2 kn L / H, and the block on
  // it oscillates at omega = sqrt(k / m) = 316 rad/s. Semi-implicit Euler is stable for
  // dt < 2 / omega (6.3 ms); the dashpot lowers the limit to 2 / omega (sqrt(1 + zeta²) - zeta)
  // (3.9 ms). Rocking is softer (omega² ≈ kn L / (m H)). dt = 1e-4 s is 39 times below the limit
  // and resolves the ~10 ms impact in ~100 steps.
  const double k = 2.0 * params.kn * L / params.H;
  const double c = 2.0 * zeta * std::sqrt(k * block.m);  // N s/m², along the contact normal
  constexpr double dt = 1.0e-4;
  const long steps = std::lround(duration / dt);

  for (long step = 0; step < steps; ++step) {
    double fx = 0.0, fy = -block.m * g, torque = 0.0;
    const rockcontact::PairContact r = contact.evaluate(block_xy, block.pose, base_xy, base_pose);
    if (r.has_point) {
      // The library gives the elastic normal force on the block (polygon a); damping is the
      // host's: a dashpot on the normal velocity of the block's material point at r.point.
      const double f = std::hypot(r.force[0], r.force[1]);
      const double nx = r.force[0] / f, ny = r.force[1] / f;
      const double rx = r.point[0] - block.pose.x, ry = r.point[1] - block.pose.y;
      const double vn = (block.vx - block.w * ry) * nx + (block.vy + block.w * rx) * ny;
      // A dashpot would pull the block back while it leaves; contacts push only.
      const double fn = std::max(0.0, f - c * vn);
      fx += fn * nx;
      fy += fn * ny;
      torque += rx * fn * ny - ry * fn * nx;
    }
    // Semi-implicit (symplectic) Euler: new velocities first, positions from them.
    block.vx += dt * fx / block.m;
    block.vy += dt * fy / block.m;
    block.w += dt * torque / block.I;
    block.pose.x += dt * block.vx;
    block.pose.y += dt * block.vy;
    block.pose.theta += dt * block.w;
  }

  const rockcontact::PairContact rest = contact.evaluate(block_xy, block.pose, base_xy, base_pose);
  // Static solution. On the L x d intersection polygon the block's exit distance is d (to its
  // bottom) except within d of its sides, and the base's is the depth below its top, so eq. 11
  // gives F = kn (2 L d - d²) / H (the d² is the two corner triangles); F = m g at rest:
  const double delta = L - std::sqrt(L * L - block.m * g * params.H / params.kn);
  // After 1 s the transient has decayed by exp(-zeta omega t) ~ e^-150, and at rest the step's
  // forces balance exactly, so only roundings remain: a 1 m coordinate against a 0.1 mm depth
  // (~1e-12 relative). 1e-9 leaves a wide margin; the first-order rest m g H / (2 kn L) would
  // miss by d / (2 L) = 4.9e-5. The force must carry the weight to the same 1e-9.
  const double pen_err = std::abs(rest.penetration - delta) / delta;
  const double weight = block.m * g;
  const double force_err = std::abs(rest.force[1] - weight) / weight;
  const bool ok = pen_err <= 1e-9 && force_err <= 1e-9 && std::abs(rest.force[0]) <= 1e-9 * weight;

  std::printf("rockcontact %s: %ld steps of %.3g s, block at (%.6f, %.6f) m, %.3g rad\n",
              ROCKCONTACT_VERSION_STRING, steps, dt, block.pose.x, block.pose.y, block.pose.theta);
  std::printf("penetration %.9e m, static L - sqrt(L² - m g H / kn) %.9e m, relative error %.2e (<= 1e-9)\n",
              rest.penetration, delta, pen_err);
  std::printf("normal force (%.6e, %.6e) N/m, weight %.6e N/m, relative error %.2e (<= 1e-9)\n",
              rest.force[0], rest.force[1], weight, force_err);
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
