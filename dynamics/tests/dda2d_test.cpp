#define BOOST_TEST_MODULE dynamics_dda2d
#include <boost/test/unit_test.hpp>

// Explicit 2D DDA (dynamics/dda2d.hpp) against analytic references: free rotation, free fall,
// the critical time step in closed form, the paper's parameter sets, and bad input.

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"

namespace {

using namespace rockcontact::dynamics;
using namespace rockcontact::dynamics::testing;
using rockcontact::kernel::InvalidPolygon;

double polygon_area(const std::vector<Point2>& v) {
  double twice = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Point2& p = v[i];
    const Point2& q = v[(i + 1) % v.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice;
}

bool message_has(const std::exception& e, const std::string& text) {
  return std::string(e.what()).find(text) != std::string::npos;
}

}  // namespace

// (1) A deformable unit square spinning freely at 10 rad/s (E = 0.1 GPa, no gravity, no
// contact), dt = 1e-3 s, 1000 steps: Δr0 = 0.01 per step, 10 rad in all. With no force the
// acceleration is exactly zero, so d' stays (0, 0, 10, 0, 0, 0) and every step is the exact
// rotation R(0.01): the area, the centroid and the vertices (those of the start turned by
// 10 rad about the centroid) are kept up to round-off. The first-order map I + Δr0 J (the
// T map of eq. 3 applied to the rotation) has determinant 1 + Δr0², so it would multiply the
// area by (1 + 1e-4)^1000 = 1.105 (+10.5 %).
// Tolerances: each step rounds every coordinate (~1e-16 relative to the 3.5 m position) and
// cos/sin; 1000 steps accumulate at most ~1e-13, so 1e-12 bounds the drift with margin.
BOOST_AUTO_TEST_CASE(free_rotation_keeps_area_and_shape) {
  BlockSpec spec = block("spinner", square(2.5, 1.5, 1.0));
  spec.material.youngs_modulus = 1.0e8;
  spec.omega = 10.0;
  Dda2d sim({spec}, frictionless(), params(1.0e-3));
  const Point2 c0 = sim.blocks()[0].centroid;
  const double a0 = polygon_area(sim.blocks()[0].vertices);
  for (int n = 0; n < 1000; ++n) sim.step();
  const BlockState& s = sim.blocks()[0];

  const double area_ratio = polygon_area(s.vertices) / a0;
  const double first_order = std::pow(1.0 + 0.01 * 0.01, 1000);
  BOOST_TEST_MESSAGE("free rotation: area ratio - 1 = " << area_ratio - 1.0
                     << " (first-order T map: " << first_order - 1.0 << ")");
  BOOST_TEST(std::fabs(area_ratio - 1.0) <= 1e-12);
  BOOST_TEST(std::fabs(s.area / a0 - 1.0) <= 1e-12);
  BOOST_TEST(std::fabs(first_order - area_ratio) > 0.1);
  BOOST_TEST(std::hypot(s.centroid.x - c0.x, s.centroid.y - c0.y) <= 1e-12);
  BOOST_TEST(std::fabs(s.rotation - 10.0) <= 1e-12);
  BOOST_TEST(s.velocity[2] == 10.0);
  for (std::size_t k = 3; k < 6; ++k) BOOST_TEST(s.velocity[k] == 0.0);
  // The vertices are those of the start turned by 10 rad.
  const double c = std::cos(10.0), sn = std::sin(10.0);
  for (std::size_t k = 0; k < 4; ++k) {
    const Point2 p = spec.vertices[k];
    const Point2 expected{c0.x + c * (p.x - c0.x) - sn * (p.y - c0.y),
                          c0.y + sn * (p.x - c0.x) + c * (p.y - c0.y)};
    BOOST_TEST(std::hypot(s.vertices[k].x - expected.x, s.vertices[k].y - expected.y) <= 1e-12);
  }
  BOOST_TEST(std::fabs(sim.energies().total() / (0.5 * (2000.0 / 6.0) * 100.0) - 1.0) <= 1e-12);
}

// (2) Free fall under g = (0, -9.81): velocity Verlet is exact for a constant acceleration,
// x_{n+1} = x_n + h v_n + h² g / 2, so the centroid sits at c0 + g t² / 2 with t = n h and the
// velocity is g t, up to round-off. Rigid and deformable blocks alike (gravity acts on u0, v0
// only; the strain DOFs see no force). Tolerance: the drop is 1.23 m after 1000 steps of
// 5e-4 s; rounding of the vertex coordinates and of the centroid recomputed from them each step
// adds ~1e-15 m per step, 1e-12 m bounds 1000 of them.
BOOST_AUTO_TEST_CASE(free_fall_follows_g_t_squared_over_two) {
  for (const bool rigid : {true, false}) {
    BlockSpec spec = block("faller", square(-0.5, 10.0, 1.0));
    spec.rigid = rigid;
    Dda2d sim({spec}, frictionless(), params(5.0e-4, {0.0, -9.81}));
    const Point2 c0 = sim.blocks()[0].centroid;
    for (int n = 0; n < 1000; ++n) sim.step();
    const BlockState& s = sim.blocks()[0];
    const double t = sim.time();
    BOOST_TEST_CONTEXT((rigid ? "rigid" : "deformable")) {
      BOOST_TEST(t == 0.5);
      BOOST_TEST(std::fabs(s.centroid.y - (c0.y - 0.5 * 9.81 * t * t)) <= 1e-12);
      BOOST_TEST(std::fabs(s.centroid.x - c0.x) <= 1e-12);
      BOOST_TEST(std::fabs(s.velocity[1] + 9.81 * t) <= 1e-12);
      BOOST_TEST(std::fabs(s.rotation) <= 1e-15);
      // Energy: kinetic + gravitational = 0 up to the same round-off (m g drop ~ 2.4e4 J/m).
      BOOST_TEST(std::fabs(sim.energies().total()) <= 1e-12 * 2000.0 * 9.81 * 1.3);
    }
  }
}

// The critical time step in closed form. A deformable unit square (m = 2000 kg/m, E = 1 GPa,
// nu = 0.25, plane stress): about its centroid I_xx = I_yy = 1/12, I_xy = 0, so the (r0, ex, ey,
// gxy) block of M is m diag(1/6, 1/12, 1/12, 1/24) and K = E-matrix on the strain DOFs. The
// normal-strain pair (ex, ey) gives omega² = 12 E (1 ± nu) / (m (1 - nu²)), the largest
// 12 E / (m (1 - nu)) = 8e6; shear gives E / (2 (1 + nu)) / (m / 24) = 4.8e6. So
// dt_crit = 2 / sqrt(8e6) = 7.0711e-4 s. The contact with a second square is softer:
// (kn/H) L (c_A + c_B) with L = 4 m (perimeter) and c = 7/m (corner compliance of the
// deformable square: 1 + 6y² + 12x² + 6y² at x = y = 1/2, over m), i.e. 4e7 * 0.007 = 2.8e5.
// Both act on the block's degrees of freedom, so the estimate adds them (dda2d.hpp):
// dt_crit = 2 / sqrt(8e6 + 2.8e5) = 6.9505e-4 s.
BOOST_AUTO_TEST_CASE(critical_time_step_of_a_deformable_square) {
  Dda2d sim({block("A", square(0, 0, 1)), block("B", square(1.5, 0, 1))}, frictionless(),
            params(1.0e-4));
  const double expected = 2.0 / std::sqrt(12.0 * 1.0e9 / (2000.0 * 0.75) + 1.0e7 * 4.0 * 0.007);
  BOOST_TEST(std::fabs(sim.critical_time_step() / expected - 1.0) <= 1e-12);
  BOOST_TEST(sim.critical_time_step_source().find("block 'A': elastic stiffness") == 0);
  BOOST_TEST(sim.critical_time_step_source().find("plus its contacts") != std::string::npos);
}

// Rigid unit squares: the corner compliance is 1/m + r²/I = (1 + (1/2) / (1/6)) / m = 4/m,
// so omega² = (kn/H) 4 m * 8/m = 1.6e5 with kn = 1e7 Pa, H = 1 m: dt_crit = 2/400 = 5e-3 s
// (two equal blocks: the O(n) bound of dda2d.hpp, 2 (kn/H P) c, is exact here).
BOOST_AUTO_TEST_CASE(critical_time_step_of_rigid_contact) {
  BlockSpec a = block("A", square(0, 0, 1)), b = block("B", square(1.5, 0, 1));
  a.rigid = b.rigid = true;
  Dda2d sim({a, b}, frictionless(), params(1.0e-4));
  BOOST_TEST(std::fabs(sim.critical_time_step() / 5.0e-3 - 1.0) <= 1e-12);
  BOOST_TEST(sim.critical_time_step_source().find("block 'A': contacts") == 0);
}

// (5) dt above the estimate is refused with dt, the estimate and the limiting block or pair.
BOOST_AUTO_TEST_CASE(dt_above_the_critical_estimate_is_refused) {
  try {
    Dda2d({block("A", square(0, 0, 1))}, frictionless(), params(1.0e-3));
    BOOST_FAIL("dt = 1e-3 s above 7.07e-4 s was accepted");
  } catch (const StabilityError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(message_has(e, "dt = 0.001 s"));
    BOOST_TEST(message_has(e, "critical time step 0.000707107 s"));
    BOOST_TEST(message_has(e, "block 'A'"));
  }
  BlockSpec a = block("left", square(0, 0, 1)), b = block("right", square(1.5, 0, 1));
  a.rigid = b.rigid = true;
  try {
    Dda2d({a, b}, frictionless(1.0e10), params(1.0e-3));  // omega² = 1.6e8: dt_crit 1.58e-4 s
    BOOST_FAIL("dt = 1e-3 s above the contact estimate was accepted");
  } catch (const StabilityError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(message_has(e, "critical time step 0.000158114 s"));
    BOOST_TEST(message_has(e, "block 'left': contacts"));
  }
}

// The paper's parameter sets (seed 000 Tables 4-5) pass the estimate. The geometry of each
// example is rebuilt from its description (1 m blocks; 4.3 on a 30° incline; 5.1 a 0.1 m fixed
// base and H the mean of the largest and smallest edge; 5.2 triangles with a 5° angle; 5.3 a
// block with 0.05 m chamfers); the parameters are the tables'.
BOOST_AUTO_TEST_CASE(paper_parameter_sets_are_accepted) {
  struct Case {
    const char* name;
    double E, kn, dt, H;
    std::optional<FrictionLaw> friction;
    std::vector<BlockSpec> blocks;
  };
  const double t5 = std::tan(5.0 * std::numbers::pi / 180.0);
  BlockSpec base = block("base", {{-3, -1}, {3, -1}, {3, 0}, {-3, 0}});
  base.fixed = true;
  BlockSpec thin_base = block("base", {{-3, -0.1}, {3, -0.1}, {3, 0}, {-3, 0}});
  thin_base.fixed = true;
  BlockSpec incline = block("incline", {{0, 0}, {4, 0}, {0, 4 * std::tan(std::numbers::pi / 6)}});
  incline.fixed = true;
  const std::vector<Case> cases{
      {"4.1", 1e9, 1e7, 1e-4, 1.0, {}, {block("A", square(0, 0, 1)), block("B", square(1, 0, 1))}},
      {"4.2", 1e8, 1e7, 1e-3, 1.0, {},
       {base, block("top", square(-0.5, 2, 1)), block("l", square(-1, 0, 1)), block("r", square(0, 0, 1))}},
      {"4.3", 1e9, 1e7, 1e-5, 1.0, FrictionLaw{1e7, 20.0},
       {incline, block("slider", {{1, 1.7}, {1.866, 1.2}, {2.366, 2.066}, {1.5, 2.566}})}},
      {"5.1", 1e9, 5e7, 1e-4, 0.55, FrictionLaw{1e7, 20.0}, {thin_base, block("A", square(-0.5, 1, 1))}},
      {"5.2", 1e9, 5e7, 2e-5, 1.0, FrictionLaw{1e7, 20.0},
       {block("up", {{0, 0}, {1, 0}, {1, t5}}), block("down", {{0, 0.2}, {1, 0.2 - t5}, {1, 0.2}})}},
      {"5.3", 1e9, 5e7, 1e-4, 1.0, FrictionLaw{1e7, 20.0},
       {base, block("chamfered", {{0.05, 0}, {0.95, 0}, {1, 0.05}, {1, 0.95}, {0.95, 1}, {0.05, 1},
                                  {0, 0.95}, {0, 0.05}})}},
  };
  for (const Case& c : cases) {
    std::vector<BlockSpec> blocks = c.blocks;
    for (BlockSpec& b : blocks) b.material.youngs_modulus = c.E;
    ContactLaw law = frictionless(c.kn, c.H);
    law.friction = c.friction;
    BOOST_TEST_CONTEXT("example " << c.name) {
      BOOST_CHECK_NO_THROW({
        const Dda2d sim(blocks, law, params(c.dt, {0.0, -9.81}));
        BOOST_TEST_MESSAGE("example " << c.name << ": dt " << c.dt << " s, critical "
                           << sim.critical_time_step() << " s (" << sim.critical_time_step_source()
                           << ")");
      });
    }
  }
}

// The penetration monitor: a rigid 1 m square resting on a fixed base under gravity with a
// contact far too soft for its weight (kn = 1e4 Pa: the static overlap would be
// m g H / (2 kn L) = 0.98 m) sinks; once the minimum translation distance passes half the
// smaller inradius (0.25 m) the step throws, naming both blocks and the numbers. Released as
// placed (no initial-equilibrium pre-solve), so that the steps are what sinks it. The strict
// pre-solve refuses it first: its solve would move the box by the 0.98 m, more than its
// inradius (0.5 m).
BOOST_AUTO_TEST_CASE(penetration_deeper_than_half_the_inradius_stops_the_run) {
  BlockSpec base = block("base", {{-2, -1}, {2, -1}, {2, 0}, {-2, 0}});
  base.fixed = true;
  BlockSpec box = block("box", square(-0.5, 0, 1));
  box.rigid = true;
  try {
    DdaParams strict = params(1.0e-4, {0.0, -9.81});
    strict.initial_equilibrium = InitialEquilibrium::strict;
    Dda2d settled({base, box}, frictionless(1.0e4), strict);
    BOOST_FAIL("the strict pre-solve took a box its contact cannot hold");
  } catch (const StabilityError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(message_has(e, "would move block 'box' by 0.98"));
    BOOST_TEST(message_has(e, "more than its inradius (0.5 m)"));
  }
  DdaParams released = params(1.0e-4, {0.0, -9.81});
  released.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  Dda2d sim({base, box}, frictionless(1.0e4), released);
  try {
    while (sim.steps() < 10000) sim.step();
    BOOST_FAIL("the box sank without a StabilityError");
  } catch (const StabilityError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(message_has(e, "block 'base' and block 'box' overlap by"));
    BOOST_TEST(message_has(e, "(0.25 m)"));
    BOOST_TEST(sim.max_penetration() > 0.25);
    BOOST_TEST(sim.max_penetration() < 0.26);  // caught within the step that crossed the limit
  }
}

// A block placed 0.3 m deep inside its base (more than half its inradius, 0.25 m) is refused at
// the start as overlapping geometry, naming both blocks and the depth, whatever kn: it is the
// input that is wrong, not the contact's stiffness or the step.
BOOST_AUTO_TEST_CASE(blocks_overlapping_at_the_start_are_refused_as_input) {
  BlockSpec base = block("base", {{-2, -1}, {2, -1}, {2, 0}, {-2, 0}});
  base.fixed = true;
  const BlockSpec sunk = block("sunk", square(-0.5, -0.3, 1));
  for (const InitialEquilibrium presolve :
       {InitialEquilibrium::off, InitialEquilibrium::automatic, InitialEquilibrium::strict}) {
    DdaParams p = params(1.0e-4, {0.0, -9.81});
    p.initial_equilibrium = presolve;
    try {
      Dda2d({base, sunk}, frictionless(1.0e9), p);
      BOOST_FAIL("a block 0.3 m inside its base was accepted");
    } catch (const std::invalid_argument& e) {
      BOOST_TEST_MESSAGE(e.what());
      BOOST_TEST(message_has(e, "block 'base' and block 'sunk' overlap by 0.3 m at the start"));
      BOOST_TEST(message_has(e, "the starting geometry overlaps"));
    }
  }
}

// (6) A clockwise block: kernel::InvalidPolygon naming the block by its id.
BOOST_AUTO_TEST_CASE(clockwise_block_is_rejected_by_id) {
  std::vector<Point2> clockwise = square(3, 0, 1);
  std::swap(clockwise[1], clockwise[3]);
  try {
    Dda2d({block("ok", square(0, 0, 1)), block("backwards", clockwise)}, frictionless(),
          params(1.0e-4));
    BOOST_FAIL("a clockwise block was accepted");
  } catch (const InvalidPolygon& e) {
    BOOST_TEST(e.polygon() == "block 'backwards'");
    BOOST_TEST((e.reason() == InvalidPolygon::Reason::clockwise));
    BOOST_TEST(message_has(e, "backwards"));
  }
}

BOOST_AUTO_TEST_CASE(bad_parameters_are_named) {
  const auto names = [](std::vector<BlockSpec> blocks, ContactLaw law, DdaParams p,
                        const std::string& text) {
    try {
      Dda2d sim(std::move(blocks), std::move(law), p);
    } catch (const std::invalid_argument& e) {
      BOOST_TEST_MESSAGE(e.what());
      return message_has(e, text);
    }
    return false;
  };
  const std::vector<BlockSpec> one{block("A", square(0, 0, 1))};
  BOOST_TEST(names(one, frictionless(), params(0.0), "dt"));
  BOOST_TEST(names(one, frictionless(), params(std::nan("")), "dt"));
  BOOST_TEST(names(one, frictionless(-1.0), params(1e-4), "kn"));
  BOOST_TEST(names(one, frictionless(1e7, 0.0), params(1e-4), "H"));
  ContactLaw sticky = frictionless();
  sticky.friction = FrictionLaw{1e7, 95.0};
  BOOST_TEST(names(one, sticky, params(1e-4), "friction_angle_deg"));
  DdaParams damped = params(1e-4);
  damped.mass_damping = -1.0;
  BOOST_TEST(names(one, frictionless(), damped, "mass_damping"));
  BOOST_TEST(names({}, frictionless(), params(1e-4), "no blocks"));
  BOOST_TEST(names({block("A", square(0, 0, 1)), block("A", square(2, 0, 1))}, frictionless(),
                   params(1e-4), "duplicate block 'A'"));
  BlockSpec light = block("light", square(0, 0, 1));
  light.material.density = 0.0;
  BOOST_TEST(names({light}, frictionless(), params(1e-4), "block 'light': density"));
  BlockSpec soft = block("soft", square(0, 0, 1));
  soft.material.poisson_ratio = 0.5;
  BOOST_TEST(names({soft}, frictionless(), params(1e-4), "block 'soft': poisson_ratio"));
  BlockSpec moving_wall = block("wall", square(0, 0, 1));
  moving_wall.fixed = true;
  moving_wall.velocity = {1.0, 0.0};
  BOOST_TEST(names({moving_wall}, frictionless(), params(1e-4), "block 'wall': a fixed block"));
}
