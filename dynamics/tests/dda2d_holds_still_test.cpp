#define BOOST_TEST_MODULE dynamics_dda2d_holds_still
#include <boost/test/unit_test.hpp>

// Blocks that must stay where they are, and the contact dashpot, with the library's defaults:
// the elastoplastic friction law after the initial-equilibrium pre-solve (dda2d.hpp), no damping.
//
// (1) A rigid square of side a resting on a 40° slope with phi = 40.1° (the 0.1° margin of the
//     stable-block verification of block codes) for a = 0.1, 1 and 20 m: it must move < 1 mm in
//     10 s. Parameters as the docs tell a user to choose them: kn = 1e9 Pa (a fraction of the
//     rock's E = 1e10 Pa), kt = 1e9 N/m, H = a (the block's size), dt = half the critical step
//     the engine estimates, capped at 1e-4 s. With the paper's law and no pre-solve the 1 m
//     block slid 230 mm in 1 s (the spring loads from zero, overshoots the limit and ratchets);
//     measured now: 1.4e-11, 5.4e-10 and 3.3e-6 m.
// (2) Five 1 m squares stacked with 1 mm alternating offsets on a fixed floor, phi = 30°: each
//     must move < 1 mm in 10 s (measured 2.3e-9 m).
// (3) The contact dashpot of damping ratio zeta: a rigid 1 m square released at zero overlap on
//     a frictionless floor (no pre-solve) oscillates about its static depth m g H / (2 kn L) at
//     omega = sqrt(2 kn L / (H m)) = 100 rad/s; the dashpot c = 2 zeta sqrt(m k) makes it the
//     damped oscillator whose successive overshoots shrink by exp(-2 pi zeta / sqrt(1 - zeta²))
//     (0.5318 for zeta = 0.1). The force uses the step's half-step velocity (an O(omega dt) =
//     1e-3 lag) and the contact length grows by the depth (1e-3): bound 1 % on the ratio.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"

namespace {

using namespace rockcontact::dynamics;
using testing::block;
using testing::square;

constexpr double g = 9.81;
constexpr double duration = 10.0;

double distance(Point2 a, Point2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

ContactLaw frictional(double kn, double kt, double phi, double H) {
  ContactLaw law;
  law.normal.kn = kn;
  law.normal.H = H;
  law.friction = FrictionLaw{kt, phi};
  return law;
}

// dt = half the engine's estimate, at most 1e-4 s, as the docs advise.
double half_the_estimate(const std::vector<BlockSpec>& blocks, const ContactLaw& law) {
  DdaParams probe;
  probe.dt = 1e-12;
  probe.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  return std::min(1e-4, 0.5 * Dda2d(blocks, law, probe).critical_time_step());
}

// Runs for `duration` and returns the largest displacement of a movable block's centroid.
double largest_motion(const std::vector<BlockSpec>& blocks, const ContactLaw& law, double dt) {
  DdaParams params;
  params.dt = dt;
  params.gravity = {0.0, -g};
  Dda2d sim(blocks, law, params);
  BOOST_TEST(sim.initial_equilibrium().ran);
  BOOST_TEST_MESSAGE("pre-solve: " << sim.initial_equilibrium().blocks << " blocks, "
                                   << sim.initial_equilibrium().iterations << " iterations, ratio "
                                   << sim.initial_equilibrium().ratio);
  std::vector<Point2> start;
  for (const BlockState& s : sim.blocks()) start.push_back(s.centroid);
  const auto steps = static_cast<std::size_t>(std::ceil(duration / dt));
  while (sim.steps() < steps) sim.step();
  double most = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (!sim.blocks()[i].fixed) most = std::max(most, distance(start[i], sim.blocks()[i].centroid));
  }
  return most;
}

}  // namespace

BOOST_AUTO_TEST_CASE(block_on_a_slope_steeper_by_less_than_its_friction_angle_stays) {
  const double theta = 40.0 * std::numbers::pi / 180.0;
  const Vector2 along{std::cos(theta), std::sin(theta)}, up{-std::sin(theta), std::cos(theta)};
  for (const double a : {0.1, 1.0, 20.0}) {
    BOOST_TEST_CONTEXT("a = " << a << " m") {
      const double width = 3.0 * a;
      BlockSpec slope = block("slope", {{0.0, 0.0}, {width, 0.0}, {width, width * std::tan(theta)}}, true);
      const double s = 0.5 * width / std::cos(theta) - 0.5 * a;  // mid-slope
      const Point2 p{s * along.x, s * along.y};
      BlockSpec box = block("box", {p,
                                    {p.x + a * along.x, p.y + a * along.y},
                                    {p.x + a * (along.x + up.x), p.y + a * (along.y + up.y)},
                                    {p.x + a * up.x, p.y + a * up.y}});
      box.rigid = true;
      box.material.density = 2600.0;
      box.material.youngs_modulus = slope.material.youngs_modulus = 1e10;
      const std::vector<BlockSpec> blocks{slope, box};
      const ContactLaw law = frictional(1e9, 1e9, 40.1, a);
      const double moved = largest_motion(blocks, law, half_the_estimate(blocks, law));
      BOOST_TEST_MESSAGE("moved " << moved << " m in " << duration << " s");
      BOOST_TEST(moved < 1e-3);
    }
  }
}

BOOST_AUTO_TEST_CASE(stack_of_five_offset_squares_stands) {
  std::vector<BlockSpec> blocks{block("floor", {{-5, -1}, {5, -1}, {5, 0}, {-5, 0}}, true)};
  for (int k = 0; k < 5; ++k) {
    BlockSpec b = block("b" + std::to_string(k), square(k % 2 == 0 ? 0.0 : 1e-3, k, 1.0));
    b.rigid = true;
    b.material.density = 2600.0;
    blocks.push_back(b);
  }
  const ContactLaw law = frictional(1e9, 1e9, 30.0, 1.0);
  const double moved = largest_motion(blocks, law, half_the_estimate(blocks, law));
  BOOST_TEST_MESSAGE("largest motion " << moved << " m in " << duration << " s");
  BOOST_TEST(moved < 1e-3);
}

BOOST_AUTO_TEST_CASE(contact_dashpot_decays_by_the_damped_oscillator_decrement) {
  const double zeta = 0.1;
  BlockSpec box = block("box", square(-0.5, 0.0, 1.0));
  box.rigid = true;
  ContactLaw law = testing::frictionless(1e7, 1.0);
  law.damping_ratio = zeta;
  DdaParams params = testing::params(1e-5, {0.0, -g});
  params.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  Dda2d sim({block("floor", {{-2, -1}, {2, -1}, {2, 0}, {-2, 0}}, true), box}, law, params);
  const double m = sim.blocks()[1].mass, y0 = sim.blocks()[1].centroid.y;
  const double static_depth = m * g * 1.0 / (2.0 * 1e7 * 1.0);
  // The depth's local maxima over 0.3 s (about five periods).
  std::vector<double> peaks;
  double before = 0.0, now = 0.0;
  while (sim.steps() < 30000) {
    sim.step();
    const double next = y0 - sim.blocks()[1].centroid.y;
    if (sim.steps() > 2 && now > before && now >= next) peaks.push_back(now);
    before = now;
    now = next;
  }
  BOOST_TEST_REQUIRE(peaks.size() >= 3u);
  const double expected = std::exp(-2.0 * std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
  for (std::size_t k = 0; k + 1 < 3; ++k) {
    const double ratio = (peaks[k + 1] - static_depth) / (peaks[k] - static_depth);
    BOOST_TEST_MESSAGE("overshoot ratio " << ratio << " against " << expected);
    BOOST_TEST(std::fabs(ratio / expected - 1.0) <= 0.01);
  }
  BOOST_TEST(sim.energies().damping_dissipated > 0.0);
}

// (4) Static analysis (Analysis::static_equilibrium) on a column of four rigid 1 m squares
//     placed exactly touching on a fixed floor, released unloaded (no pre-solve): it relaxes
//     until the out-of-balance ratio is below 1e-9, and each contact then carries the weight of
//     the blocks above it, k m g for the k-th interface from the top (statics of the column).
//     The ratio bounds each block's unbalanced force by 1e-9 of a weight, so the contact forces,
//     summed from the top, are within 4e-9 m g: bound 1e-8 relative. No block moves sideways.
BOOST_AUTO_TEST_CASE(static_analysis_of_a_column_carries_the_weights_above) {
  std::vector<BlockSpec> blocks{block("floor", {{-2, -1}, {2, -1}, {2, 0}, {-2, 0}}, true)};
  constexpr int count = 4;
  for (int k = 0; k < count; ++k) {
    BlockSpec b = block("b" + std::to_string(k), square(-0.5, k, 1.0));
    b.rigid = true;
    blocks.push_back(b);
  }
  DdaParams params = testing::params(1e-4, {0.0, -g});
  params.analysis = Analysis::static_equilibrium;
  params.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  Dda2d sim(blocks, frictional(1e9, 1e9, 30.0, 1.0), params);
  while (sim.balance_ratio() >= 1e-9 || sim.steps() == 0) {
    BOOST_TEST_REQUIRE(sim.steps() < 100000u);
    sim.step();
  }
  BOOST_TEST_MESSAGE("static: ratio " << sim.balance_ratio() << " after " << sim.steps() << " steps");
  const double weight = sim.blocks()[1].mass * g;
  BOOST_TEST_REQUIRE(sim.contacts().size() == static_cast<std::size_t>(count));
  for (const ContactState& c : sim.contacts()) {
    const double carried = static_cast<double>(count - c.cp) * weight;  // blocks c.tp .. count
    const Vector2 f{c.normal_force.x + c.friction_force.x, c.normal_force.y + c.friction_force.y};
    BOOST_TEST_CONTEXT("contact " << c.cp << "-" << c.tp) {
      BOOST_TEST(std::fabs(-f.y / carried - 1.0) <= 1e-8);  // on CP (below) the force points down
      BOOST_TEST(std::fabs(f.x) <= 1e-8 * carried);
    }
  }
  for (const BlockState& s : sim.blocks()) BOOST_TEST(std::fabs(s.centroid.x) <= 1e-12);
}
