#define BOOST_TEST_MODULE dynamics_dda2d_groups
#include <boost/test/unit_test.hpp>

// Explicit 2D DDA (dynamics/dda2d.hpp) with non-convex blocks (convex parts sharing one set of
// DOF) and per-group contact laws (ContactLaw::interfaces), against closed forms.

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"

namespace {

using namespace rockcontact::dynamics;
using namespace rockcontact::dynamics::testing;

constexpr double g = 9.81;

// The L [0, 2] x [0, 1] ∪ [0, 1] x [1, 2], shifted by (x0, y0), CCW.
std::vector<Point2> l_shape(double x0, double y0) {
  return {{x0, y0}, {x0 + 2, y0}, {x0 + 2, y0 + 1}, {x0 + 1, y0 + 1}, {x0 + 1, y0 + 2}, {x0, y0 + 2}};
}

}  // namespace

// A rigid L spinning freely at 2 rad/s: mass and moments come from the whole outline, not from
// one part. By hand (two rectangles, parallel axes): area 3 m², centroid (5/6, 5/6), polar
// moment about it 11/6 m⁴, so with rho = 2000 the kinetic energy is ½ rho (11/6) ω² = 7333.3
// J/m. The exact rotation keeps the area. Tolerance 1e-12 relative (round-off over 500 steps,
// as for the square of dda2d_test).
BOOST_AUTO_TEST_CASE(non_convex_block_moves_as_one_body) {
  BlockSpec spec = block("L", l_shape(0.0, 0.0));
  spec.rigid = true;
  spec.omega = 2.0;
  Dda2d sim({spec}, frictionless(), params(1.0e-3, {0.0, 0.0}));
  const BlockState& s0 = sim.blocks()[0];
  BOOST_TEST(std::fabs(s0.area - 3.0) <= 1e-15);
  BOOST_TEST(std::fabs(s0.centroid.x - 5.0 / 6.0) <= 1e-15);
  BOOST_TEST(std::fabs(s0.centroid.y - 5.0 / 6.0) <= 1e-15);
  const double kinetic = 0.5 * 2000.0 * (11.0 / 6.0) * 4.0;
  BOOST_TEST(std::fabs(sim.energies().kinetic / kinetic - 1.0) <= 1e-12);
  for (int n = 0; n < 500; ++n) sim.step();
  BOOST_TEST(std::fabs(sim.blocks()[0].area / 3.0 - 1.0) <= 1e-12);
  BOOST_TEST(std::fabs(sim.blocks()[0].rotation - 1.0) <= 1e-12);
  BOOST_TEST(std::fabs(sim.energies().kinetic / kinetic - 1.0) <= 1e-12);
}

// An inverted T (bar [0, 2] x [0, 1], stem [0.5, 1.5] x [1, 2]: symmetric, so its centroid is
// above the middle of its 2 m base and uniform pressure balances it without a tilt) resting on a
// fixed floor, sunk by its static penetration: face on face the potential force is
// 2 kn L δ / H (dda2d.hpp), so δ = m g H / (2 kn L) = 6000 · 9.81 / (2e7 · 2) = 1.47 mm.
// Whichever parts of the T touch the floor, their forces must add up to the weight (where a
// partition edge crosses the contact the two parts' contributions cancel); the part potentials
// differ from the whole block's only within ~δ of a partition edge's foot, a force defect of
// order kn δ² / H = 20 N against 58 860 N. So the block stays: over 0.05 s its centroid moves by
// less than 1e-2 δ (the defect alone would move it by 20 N / (2 kn L / H) = 5e-7 m).
// Every contact is between the T and the floor, never between its parts.
BOOST_AUTO_TEST_CASE(non_convex_block_rests_at_its_static_penetration) {
  const double delta = 6000.0 * g / (2.0 * 1.0e7 * 2.0);
  BlockSpec t = block("T", {{0, -delta}, {2, -delta}, {2, 1 - delta}, {1.5, 1 - delta},
                            {1.5, 2 - delta}, {0.5, 2 - delta}, {0.5, 1 - delta}, {0, 1 - delta}});
  t.rigid = true;
  const BlockSpec floor = block("floor", {{-3, -1}, {5, -1}, {5, 0}, {-3, 0}}, true);
  Dda2d sim({floor, t}, frictionless(), params(1.0e-4, {0.0, -g}));
  const Point2 start = sim.blocks()[1].centroid;
  for (int n = 0; n < 500; ++n) sim.step();
  const Point2 end = sim.blocks()[1].centroid;
  BOOST_TEST_MESSAGE("T moved " << std::hypot(end.x - start.x, end.y - start.y) << " m, delta " << delta);
  BOOST_TEST(std::hypot(end.x - start.x, end.y - start.y) <= 1e-2 * delta);
  BOOST_TEST(!sim.contacts().empty());
  for (const ContactState& c : sim.contacts()) {
    BOOST_TEST(c.cp == 0u);
    BOOST_TEST(c.tp == 1u);
  }
}

// A clockwise or self-intersecting outline is not a non-convex block: the error names it.
BOOST_AUTO_TEST_CASE(bad_non_convex_outline_is_named) {
  std::vector<Point2> clockwise = l_shape(0.0, 0.0);
  std::reverse(clockwise.begin(), clockwise.end());
  const std::vector<Point2> bow_tie{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  for (const auto& outline : {clockwise, bow_tie}) {
    try {
      Dda2d sim({block("bad", outline)}, frictionless(), params(1.0e-3, {0.0, 0.0}));
      BOOST_ERROR("accepted a bad outline");
    } catch (const std::invalid_argument& e) {
      BOOST_TEST_MESSAGE(e.what());
      BOOST_TEST(std::string(e.what()).find("block 'bad'") != std::string::npos);
    }
  }
}

// Two rigid 1 m x 0.2 m slabs launched at 1 m/s along a fixed floor, resting on it at their
// static penetration (slabs, so that the friction torque about the centroid, μ m g h / 2, barely
// rocks them): the scene's default friction angle is 10°, but an interface of 40° joins the
// floor's group and the group of "rough". Coulomb friction stops each after v² / (2 g tan φ):
// 0.0607 m (40°) and 0.289 m (10°). The penalty contact adds its stick start-up: friction
// builds on the spring kt over limit / (kt v) of travel (0.3 mm at 40°, 0.07 mm at 10°) with less
// than the full deceleration, lengthening the run by at most that. Tolerance 5 % (3 mm and
// 14 mm). Each block meets only the floor (they start 3 m apart and stop well before meeting).
BOOST_AUTO_TEST_CASE(interfaces_set_friction_per_pair_of_groups) {
  const double h = 0.2, m = 2000.0 * h, sink = m * g / (2.0 * 1.0e7);
  const auto square = [&](std::string id, double x) {
    BlockSpec b = block(std::move(id), {{x, -sink}, {x + 1, -sink}, {x + 1, h - sink}, {x, h - sink}});
    b.rigid = true;
    b.velocity = {1.0, 0.0};
    return b;
  };
  BlockSpec floor = block("floor", {{-2, -1}, {10, -1}, {10, 0}, {-2, 0}}, true);
  floor.group = "floor";
  BlockSpec rough = square("rough", 0.0), smooth = square("smooth", 3.0);
  rough.group = "rough";
  ContactLaw l = frictionless();
  l.friction = FrictionLaw{1.0e7, 10.0};
  l.interfaces.push_back({{"rough", "floor"}, 1.0e7, FrictionLaw{1.0e7, 40.0}});
  Dda2d sim({floor, rough, smooth}, l, params(1.0e-4, {0.0, -g}));
  const double rough0 = sim.blocks()[1].centroid.x, smooth0 = sim.blocks()[2].centroid.x;
  while (sim.steps() < 8000) sim.step();  // 0.8 s: both have stopped (v / (g tan φ) = 0.12 s, 0.58 s)
  const auto stop = [](double phi_deg) { return 1.0 / (2.0 * g * std::tan(phi_deg * std::numbers::pi / 180.0)); };
  const double rough_run = sim.blocks()[1].centroid.x - rough0;
  const double smooth_run = sim.blocks()[2].centroid.x - smooth0;
  BOOST_TEST_MESSAGE("rough " << rough_run << " m (Coulomb " << stop(40.0) << "), smooth " << smooth_run
                              << " m (Coulomb " << stop(10.0) << ")");
  BOOST_TEST(std::fabs(rough_run / stop(40.0) - 1.0) <= 0.05);
  BOOST_TEST(std::fabs(smooth_run / stop(10.0) - 1.0) <= 0.05);
  // Stopped, up to the undamped stick spring's oscillation: a stretch of at most limit / kt at
  // omega = sqrt(kt / m), i.e. a speed of at most tan φ g sqrt(m / kt) (0.052 and 0.011 m/s).
  const auto jitter = [&](double phi_deg) {
    return std::tan(phi_deg * std::numbers::pi / 180.0) * g * std::sqrt(m / 1.0e7);
  };
  BOOST_TEST(std::fabs(sim.blocks()[1].velocity[0]) <= jitter(40.0));
  BOOST_TEST(std::fabs(sim.blocks()[2].velocity[0]) <= jitter(10.0));
}

// Interfaces are checked like the defaults and at most one per pair of groups.
BOOST_AUTO_TEST_CASE(bad_interfaces_are_named) {
  ContactLaw l = frictionless();
  l.interfaces.push_back({{"a", "b"}, -1.0, std::nullopt});
  try {
    Dda2d sim({block("x", {{0, 0}, {1, 0}, {0, 1}})}, l, params(1.0e-3, {0.0, 0.0}));
    BOOST_ERROR("accepted kn < 0");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("interface between groups 'a' and 'b': kn") != std::string::npos);
  }
  l.interfaces = {{{"a", "b"}, 1.0e7, std::nullopt}, {{"b", "a"}, 2.0e7, std::nullopt}};
  try {
    Dda2d sim({block("x", {{0, 0}, {1, 0}, {0, 1}})}, l, params(1.0e-3, {0.0, 0.0}));
    BOOST_ERROR("accepted a repeated interface");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("is given twice") != std::string::npos);
  }
}
