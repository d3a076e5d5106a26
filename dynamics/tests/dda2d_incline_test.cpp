#define BOOST_TEST_MODULE dynamics_dda2d_incline
#include <boost/test/unit_test.hpp>

// (4) A block sliding on a 30° incline (seed 000 §4.3, Table 4 row 4.3: kn 1e7 Pa, H 1 m,
// kt 1e7 N/m, dt 1e-5 s, rho 2000, E 1 GPa), phi = 0, 10, 20°, first as the paper runs it (its
// friction law, the block released as placed), then with the library's defaults (the
// elastoplastic law after the initial-equilibrium pre-solve, dda2d.hpp). The incline is a fixed
// triangle; the slider a rigid L x h block (L = 1 m along the incline) with its base on the
// incline face. Both are built from exact multiples of (cos 30°, -sin 30°) and (sin 30°,
// cos 30°), so the base lies exactly on the face (an exact touch, zero overlap) unless sunk on
// purpose. The displacement is the centroid's, along the incline, after 0.2 s.
//
// ## Reference: eq. 30 and when it holds
// A rigid-plastic contact (the analytic model of eq. 30) slides at a = g (sin θ - cos θ tan φ)
// from t = 0: l = a t² / 2. The contact of the paper differs in two elastic ways:
//   * the normal penalty: starting from zero overlap the slider sinks into the incline and its
//     normal force oscillates (undamped) between 0 and 2 m g cos θ at omega_n =
//     sqrt(2 kn L / (H m)) = 100 rad/s for the square; while it slides, friction is
//     tan φ |f_n|, whose time average is still tan φ m g cos θ, so l stays eq. 30 up to a
//     bounded term tan φ g cos θ (1 - cos omega_n t) / omega_n² <= 6e-4 m;
//   * the tangential penalty: a new contact starts in stick with d = 0 (§3.2.5), and the
//     slider moves on the spring kt until kt |d_tan| reaches the Coulomb limit. From zero
//     overlap, both the normal penetration (g cos θ t²/2) and the slip (g sin θ t²/2) start
//     from zero, so the limit tan φ (2 kn L / H) g cos θ t²/2 beats the spring force
//     kt g sin θ t²/2 only when tan φ > kt tan θ / (2 kn L / H) = tan 16.1°. phi = 0 and 10°
//     therefore slide from the first steps and follow eq. 30 (measured errors 3e-14 and
//     2.5e-4; bound 1 %), while phi = 20° sticks first (asserted below).
// A stick phase on the spring leaves the slider faster than eq. 30 predicts: with the full
// normal force N = m g cos θ from the start, the slider obeys m x'' = m g sin θ - kt x, so
//   x = (g sin θ / w²) (1 - cos w t),  w = sqrt(kt / m),  until 1 - cos(w t_s) = r = tan φ / tan θ,
// then slides at a from x_s = r g sin θ / w² with v_s = (g sin θ / w) sin(w t_s), i.e.
//   l_ep(t) = x_s + v_s (t - t_s) + a (t - t_s)² / 2,
// the closed form of the same elastic-plastic contact. For the 1 m square (w = 70.7 rad/s,
// phi = 20°) v_s exceeds a t_s by 0.034 m/s and eq. 30 is short by 19 % at 0.2 s (the offset
// decays only as 1/t: 4 % at 1 s); it tends to eq. 30 as kt -> infinity (v_s - a t_s ~ 1/w).
// The zero-overlap phi = 20° run is reported against both references, not asserted: its
// stick phase runs under an oscillating normal force, for which no closed form exists.
//
// ## Settled start: the elastic-plastic closed form
// Sunk by the static overlap δ = m g cos θ H / (2 kn L) (where 2 kn L δ / H balances the
// weight), the slider starts with the full normal force and no normal oscillation, which is
// exactly the setting of l_ep. A 1 m x 0.5 m slider keeps the friction torque's rocking small
// (the tilt moves the contact point by ~ tilt · h/2, a relative effect growing as h²: measured
// 0.96 % for h = 1 m, 0.26 % for h = 0.5 m, 0.05 % for 0.25 m at phi = 20°). Bound: 1 %.
//
// ## Defaults: eq. 30 from the first step
// The pre-solve settles the slider with its tangential spring locked, so the run starts with the
// full normal force and the spring already holding m g sin θ, beyond the Coulomb limit for
// phi < 30°: the slider slides at the limit from the first step, with no normal oscillation and
// no stick phase, which is eq. 30's rigid-plastic contact. What is left is the friction torque's
// rocking (as above) and the elastic slip the spring gives back: measured 1.4e-4 (h = 1 m) and
// 5e-6 (h = 0.5 m) of eq. 30 at phi = 20°. Bound: 1 %, from zero overlap for both heights; the
// friction dissipation is tan φ m g cos θ l to the same 1 % for h = 0.5 m (measured 0.01 %; the
// 1 m slider's rocking moves its mean normal force by 1.2 %, not asserted).
//
// ## Energy
// kinetic + gravitational + contact work is conserved up to velocity Verlet's O((omega h)²)
// error, omega h <= 1e-3 here: bound 1e-6 of the gravitational energy released (measured
// ~2e-9). In the settled runs the slider slips at the limit tan φ m g cos θ over l - x_s
// (x_s is the spring's elastic stretch, released when sliding starts), which is the friction
// dissipation to the same 1 % (measured 0.01 % and 0.1 % for phi = 10°, 20°).
//
// ## Energy balance over seconds
// The 1 m x 0.5 m slider at phi = 20° on a 14 m incline for 3 s (8.2 m down the slope), after
// the pre-solve and released unloaded at zero overlap (its normal spring then oscillates and
// its tangential spring sticks first), each without and with contact dashpots (zeta = 0.1), dt
// half the engine's critical estimate (2.5 ms, 2.3 ms with the dashpots): Energies::total() must
// keep its start value, after every step, to within 1 % of the largest magnitude any term
// reaches (the gravitational energy released, 4.0e4 J/m at the end). The contact term is the
// trapezoid-rule work of the contact forces, so velocity Verlet closes the balance up to its
// O((omega h)²) term, which a steady slide does not excite; friction's share is the return
// mapping's dissipation over the same slip. Measured: 3.9e-8 and 3.4e-8 pre-solved, 3.9e-6 and
// 1.5e-6 released unloaded (zeta 0 and 0.1), of the largest term.

#include <cmath>
#include <numbers>
#include <vector>

#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"

namespace {

using namespace rockcontact::dynamics;
namespace testing = rockcontact::dynamics::testing;

constexpr double g = 9.81;
constexpr double theta = std::numbers::pi / 6.0;
const double cos30 = std::cos(theta), sin30 = std::sin(theta);
constexpr double kn = 1.0e7, kt = 1.0e7, duration = 0.2;

double tan_deg(double phi) { return std::tan(phi * std::numbers::pi / 180.0); }

double eq30(double phi, double t) { return 0.5 * g * (sin30 - cos30 * tan_deg(phi)) * t * t; }

// x_s above: the stretch of the tangential spring when sliding starts, m.
double stick_stretch(double phi, double m) { return tan_deg(phi) / std::tan(theta) * g * sin30 * m / kt; }

// l_ep(t) above, for a slider of mass m (kg/m) starting in stick under its full weight.
double elastic_plastic(double phi, double m, double t) {
  const double r = tan_deg(phi) / std::tan(theta);
  if (r == 0.0) return eq30(phi, t);
  const double w = std::sqrt(kt / m);
  const double a = g * (sin30 - cos30 * tan_deg(phi));
  const double ts = std::acos(1.0 - r) / w;
  const double xs = stick_stretch(phi, m);
  const double vs = g * sin30 / w * std::sin(w * ts);
  return xs + vs * (t - ts) + 0.5 * a * (t - ts) * (t - ts);
}

struct Run {
  double along = 0.0;  // centroid displacement along the incline, m
  double mass = 0.0;   // kg/m
  bool sliding_at_step_10 = false;
  Energies energies;
};

// paper: seed 000's friction law, released as placed; else the defaults.
Run slide(double phi, double height, double sink, bool paper = true) {
  const Vector2 t{cos30, -sin30}, n{sin30, cos30};
  const auto at = [&](double along, double up) {
    return Point2{along * t.x + up * n.x, along * t.y + up * n.y};
  };
  BlockSpec incline;
  incline.id = "incline";
  incline.fixed = true;
  incline.vertices = {{-4.0 * cos30, -4.0 * sin30}, at(4.0, 0.0), at(-4.0, 0.0)};
  BlockSpec slider;
  slider.id = "slider";
  slider.rigid = true;
  slider.vertices = {at(-0.5, -sink), at(0.5, -sink), at(0.5, height - sink), at(-0.5, height - sink)};
  ContactLaw law;
  law.normal.kn = kn;
  law.normal.H = 1.0;
  law.friction = FrictionLaw{kt, phi};
  DdaParams params;
  params.dt = 1.0e-5;
  params.gravity = {0.0, -g};
  if (paper) {
    law.friction->model = rockcontact::contact::FrictionModel::paper;
    params.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  }
  Dda2d sim({incline, slider}, law, params);
  const Point2 c0 = sim.blocks()[1].centroid;
  Run r;
  r.mass = sim.blocks()[1].mass;
  while (sim.steps() < 20000) {
    sim.step();
    if (sim.steps() == 10) r.sliding_at_step_10 = !sim.contacts().empty() && sim.contacts()[0].sliding;
  }
  const Point2 c = sim.blocks()[1].centroid;
  r.along = (c.x - c0.x) * t.x + (c.y - c0.y) * t.y;
  r.energies = sim.energies();
  BOOST_TEST_MESSAGE((paper ? "paper, " : "defaults, ") << "phi " << phi << "°, h " << height << " m, sunk "
                     << sink << " m: l = " << r.along
                     << " m; eq. 30 " << eq30(phi, duration) << " m (error "
                     << r.along / eq30(phi, duration) - 1.0 << "), elastic-plastic "
                     << elastic_plastic(phi, r.mass, duration) << " m (error "
                     << r.along / elastic_plastic(phi, r.mass, duration) - 1.0
                     << "); friction dissipated " << r.energies.friction_dissipated
                     << " J/m, energy total " << r.energies.total() << " J/m of gravitational "
                     << r.energies.gravitational);
  BOOST_TEST(std::fabs(r.energies.total()) <= 1e-6 * std::fabs(r.energies.gravitational));
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(slider_from_zero_overlap_follows_eq_30_below_the_stick_threshold) {
  for (const double phi : {0.0, 10.0}) {
    BOOST_TEST_CONTEXT("phi = " << phi) {
      const Run r = slide(phi, 1.0, 0.0);
      BOOST_TEST(r.sliding_at_step_10);
      BOOST_TEST(std::fabs(r.along / eq30(phi, duration) - 1.0) <= 0.01);
    }
  }
  const Run r = slide(20.0, 1.0, 0.0);
  BOOST_TEST(!r.sliding_at_step_10);  // above tan 16.1°: the new contact sticks first
}

BOOST_AUTO_TEST_CASE(settled_slider_follows_the_elastic_plastic_closed_form) {
  const double height = 0.5, mass = 2000.0 * height;
  const double sink = mass * g * cos30 / (2.0 * kn * 1.0);
  for (const double phi : {0.0, 10.0, 20.0}) {
    BOOST_TEST_CONTEXT("phi = " << phi) {
      const Run r = slide(phi, height, sink);
      BOOST_TEST(std::fabs(r.along / elastic_plastic(phi, mass, duration) - 1.0) <= 0.01);
      const double dissipated = tan_deg(phi) * mass * g * cos30 * (r.along - stick_stretch(phi, mass));
      BOOST_TEST(std::fabs(r.energies.friction_dissipated - dissipated) <= 0.01 * dissipated + 1e-9);
    }
  }
}

BOOST_AUTO_TEST_CASE(default_law_slides_by_eq_30_from_the_first_step) {
  for (const double height : {1.0, 0.5}) {
    const double mass = 2000.0 * height;
    for (const double phi : {0.0, 10.0, 20.0}) {
      BOOST_TEST_CONTEXT("h = " << height << ", phi = " << phi) {
        const Run r = slide(phi, height, 0.0, false);
        BOOST_TEST(std::fabs(r.along / eq30(phi, duration) - 1.0) <= 0.01);
        if (height == 0.5) {  // the 1 m slider's rocking moves its normal force by ~1 % (1.2 % measured)
          const double dissipated = tan_deg(phi) * mass * g * cos30 * r.along;
          BOOST_TEST(std::fabs(r.energies.friction_dissipated - dissipated) <= 0.01 * dissipated + 1e-9);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(energy_balance_closes_over_seconds_of_sliding) {
  const Vector2 t{cos30, -sin30}, n{sin30, cos30};
  const auto at = [&](double along, double up) {
    return Point2{along * t.x + up * n.x, along * t.y + up * n.y};
  };
  std::vector<BlockSpec> blocks{
      testing::block("incline", {at(-2.0, 0.0), {-2.0 * cos30, -12.0 * sin30}, at(12.0, 0.0)}, true),
      testing::block("slider", {at(-0.5, 0.0), at(0.5, 0.0), at(0.5, 0.5), at(-0.5, 0.5)})};
  blocks[1].rigid = true;
  for (const bool settled : {true, false}) {
    for (const double zeta : {0.0, 0.1}) {
      BOOST_TEST_CONTEXT("zeta = " << zeta << (settled ? ", pre-solved" : ", released unloaded")) {
        ContactLaw law;
        law.normal.kn = kn;
        law.normal.H = 1.0;
        law.friction = FrictionLaw{kt, 20.0};
        law.damping_ratio = zeta;
        DdaParams params = testing::params(1e-12, {0.0, -g});
        params.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
        params.dt = 0.5 * Dda2d(blocks, law, params).critical_time_step();
        params.initial_equilibrium = settled ? InitialEquilibrium::automatic : InitialEquilibrium::off;
        Dda2d sim(blocks, law, params);
        testing::EnergyBalance balance(sim.energies());
        const Point2 c0 = sim.blocks()[1].centroid;
        while (sim.time() < 3.0) {
          sim.step();
          balance.record(sim.energies());
        }
        const Point2 c = sim.blocks()[1].centroid;
        const Energies e = sim.energies();
        BOOST_TEST_MESSAGE("dt " << params.dt << " s, " << sim.steps() << " steps: slid "
                           << (c.x - c0.x) * t.x + (c.y - c0.y) * t.y << " m; kinetic " << e.kinetic
                           << ", gravitational " << e.gravitational << ", contact " << e.contact
                           << ", friction " << e.friction_dissipated << ", damping " << e.damping_dissipated
                           << " J/m; imbalance " << balance.drift() << " J/m of the largest term "
                           << balance.largest_term() << " J/m (" << balance.ratio() << ")");
        BOOST_TEST(balance.ratio() < 0.01);
      }
    }
  }
}
