#define BOOST_TEST_MODULE dynamics_dda2d_equilibrium
#include <boost/test/unit_test.hpp>

// The initial equilibrium of the 2D DDA (dda2d.hpp, "Initial equilibrium"), with the defaults a
// user gets ("auto"):
//
// (1) A joint-cut mass: a 12 x 12 grid of deformable 1 m blocks on a fixed floor (rho 2700,
//     E 2 GPa, nu 0.25, kn 2 GPa, kt 1 GN/m, phi 30°), the blocks in exact touch as a cut
//     leaves them, ordered as the cut lists them and the floor after them. The pre-solve must
//     settle every block to the tolerance, and the floor must then carry the mass's weight:
//     the sum of the floor's normal forces equals 144 m g up to the blocks' out-of-balance,
//     at most 144 x 1e-6 x F_ref (F_ref, the largest contact force, is the bottom row's 12 m g),
//     a relative 1.2e-5 of the weight.
// (2) A column that topples: 0.2 m wide and 2 m high on a 30° slope (b / h = 0.1 < tan 30°,
//     phi 45°, so it does not slide). "auto" starts it from its given state and names it;
//     strict refuses it, naming it.
// (3) A mass the pre-solve does not settle: the mass of (1) held to a tolerance (10⁻¹⁷) below
//     what the sums of its forces can resolve (F_ref is 3.2·10⁵ N/m, a block's forces sums of
//     ~10 terms of that size: rounding leaves ~10⁻¹⁶ of it). "auto" starts the run from the
//     least out-of-balance state it reported on the way (its progress reports every Newton
//     iteration and every 100th of the relaxation), not from where the relaxation gave up;
//     and that state's translational balance, recomputed here from the blocks' weights and the
//     contact forces, is within the ratio it reports.
// (4) Columns of square blocks of side L on the floor, leaning 10⁻³ rad (a block's centre offset
//     by 10⁻³ of its height), below and above the height where such a column buckles under its
//     own weight. Each joint closes over its width with the pressure 2 kn / H per metre of
//     overlap (dda2d.hpp), a rocking stiffness 2 kn L³ / (12 H) per radian, one joint every L of
//     height: EI = 2 kn L⁴ / (12 H) (constant-strain blocks do not bend: the joints are all the
//     column's flexibility). Greenhill's free column under its weight q = rho g L buckles at
//     q h³ = 7.84 EI: h_cr = 46.2 m for 1 m blocks at kn = 2 GPa. The family: L = 1 m, 0.5 m
//     and 2 m at kn = 2 GPa (h_cr 46.2, 23.1, 92.4 m), and L = 1 m at kn = 20 GPa (99.6 m).
//     At 0.85 h_cr the pre-solve settles every block; at 1.15 h_cr its stability probe names
//     the column's upper blocks, not its base, and they start as given; strict refuses it.
//     The margins cover the continuous formula against discrete joints and the base joint on
//     the floor: the probe's growth measured (h / h_cr)³ to 3 % at 46, 50 and 56 m.
// (5) The 8 x 50 mass of (1)'s blocks: its edge columns stand 50 m tall, above h_cr, and lean
//     outward as the rows below spread under their weight (Poisson). The probe names blocks of
//     the two edge columns only, their top blocks among them, and the rest settles to the
//     tolerance.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"

namespace {

using namespace rockcontact::dynamics;
using testing::block;
using testing::square;

constexpr double g = 9.81;

ContactLaw rock_joints(double phi) {
  ContactLaw law;
  law.normal.kn = 2.0e9;
  law.normal.H = 1.0;
  law.friction = FrictionLaw{1.0e9, phi};
  return law;
}

Material rock() { return {2700.0, 2.0e9, 0.25}; }

// The defaults a user gets, with gravity.
DdaParams gravity_params() {
  DdaParams params;
  params.gravity = {0.0, -g};
  return params;
}

// A joint-cut mass of width x height deformable 1 m blocks on a fixed floor, the floor last.
std::vector<BlockSpec> jointed_mass(int width, int height) {
  std::vector<BlockSpec> blocks;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      BlockSpec b = block("b" + std::to_string(r) + "_" + std::to_string(c), square(c, r, 1.0));
      b.material = rock();
      blocks.push_back(b);
    }
  }
  BlockSpec floor = block("floor", {{-2, -1}, {width + 2.0, -1}, {width + 2.0, 0}, {-2, 0}}, true);
  floor.material = rock();
  blocks.push_back(floor);
  return blocks;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_joint_cut_mass_settles_with_its_weight_on_the_floor) {
  constexpr int n = 12;
  const std::vector<BlockSpec> blocks = jointed_mass(n, n);
  const Dda2d sim(blocks, rock_joints(30.0), gravity_params());
  const Equilibrium& e = sim.initial_equilibrium();
  BOOST_TEST_MESSAGE("pre-solve: " << e.blocks << " blocks, " << e.iterations << " iterations, ratio "
                                   << e.ratio << ", " << e.seconds << " s");
  BOOST_TEST(e.converged);
  BOOST_TEST(e.blocks == static_cast<std::size_t>(n * n));
  BOOST_TEST(e.unsettled.empty());
  BOOST_TEST(e.ratio < 1e-6);
  double carried = 0.0;
  for (const ContactState& c : sim.contacts()) {
    const bool on_floor = sim.blocks()[c.cp].id == "floor" || sim.blocks()[c.tp].id == "floor";
    if (on_floor) carried += std::abs(c.normal_force.y + c.friction_force.y);
  }
  const double weight = n * n * rock().density * g;
  BOOST_TEST_MESSAGE("the floor carries " << carried << " N/m of " << weight << " N/m");
  BOOST_TEST(std::abs(carried - weight) <= 1.2e-5 * weight);
}

BOOST_AUTO_TEST_CASE(a_column_that_topples_starts_as_given) {
  const double theta = 30.0 * std::numbers::pi / 180.0;
  const Vector2 along{std::cos(theta), std::sin(theta)}, up{-std::sin(theta), std::cos(theta)};
  BlockSpec slope = block("slope", {{0.0, 0.0}, {8.0, 0.0}, {8.0, 8.0 * std::tan(theta)}}, true);
  const Point2 p{4.0 * along.x, 4.0 * along.y};
  const auto at = [&](double s, double h) { return Point2{p.x + s * along.x + h * up.x, p.y + s * along.y + h * up.y}; };
  BlockSpec column = block("column", {at(0.0, 0.0), at(0.2, 0.0), at(0.2, 2.0), at(0.0, 2.0)});
  column.rigid = true;
  const std::vector<BlockSpec> blocks{slope, column};
  DdaParams params = gravity_params();
  const Dda2d sim(blocks, rock_joints(45.0), params);
  BOOST_TEST(sim.initial_equilibrium().unsettled == std::vector<std::string>{"column"});
  BOOST_TEST((sim.blocks()[1].vertices == column.vertices));  // as given
  params.initial_equilibrium = InitialEquilibrium::strict;
  try {
    const Dda2d strict(blocks, rock_joints(45.0), params);
    BOOST_FAIL("the strict pre-solve took a column that topples");
  } catch (const StabilityError& error) {
    BOOST_TEST_MESSAGE(error.what());
    BOOST_TEST(std::string(error.what()).find("block 'column'") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(a_mass_that_does_not_settle_starts_from_its_least_out_of_balance_state) {
  const std::vector<BlockSpec> blocks = jointed_mass(12, 12);
  DdaParams params = gravity_params();
  params.equilibrium_tolerance = 1e-17;
  double least = std::numeric_limits<double>::infinity();
  params.equilibrium_progress = [&](std::size_t, double ratio) { least = std::min(least, ratio); };
  const Dda2d sim(blocks, rock_joints(30.0), params);
  const Equilibrium& e = sim.initial_equilibrium();
  BOOST_TEST_MESSAGE("pre-solve: " << e.iterations << " iterations, ratio " << e.ratio << ", least reported "
                                   << least << ", " << e.seconds << " s");
  BOOST_TEST_REQUIRE(!e.converged);  // the case this test is about
  BOOST_TEST(e.ratio == least);
  // F_ref: the largest block weight or normal contact force.
  double reference = 0.0;
  for (const BlockState& b : sim.blocks()) reference = std::max(reference, b.mass * g);
  for (const ContactState& c : sim.contacts()) reference = std::max(reference, std::hypot(c.normal_force.x, c.normal_force.y));
  // Released, a contact whose locked friction passed its Coulomb limit slides at the limit
  // (dda2d.hpp): only the blocks with no sliding contact keep the pre-solve's forces.
  std::vector<Vector2> force(sim.blocks().size());
  std::vector<char> slides(sim.blocks().size(), 0);
  for (std::size_t i = 0; i < force.size(); ++i) force[i] = {0.0, -sim.blocks()[i].mass * g};
  for (const ContactState& c : sim.contacts()) {
    const Vector2 f{c.normal_force.x + c.friction_force.x, c.normal_force.y + c.friction_force.y};
    force[c.cp] = {force[c.cp].x + f.x, force[c.cp].y + f.y};
    force[c.tp] = {force[c.tp].x - f.x, force[c.tp].y - f.y};
    if (c.sliding) slides[c.cp] = slides[c.tp] = 1;
  }
  double worst = 0.0;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < force.size(); ++i) {
    if (sim.blocks()[i].fixed || slides[i]) continue;
    worst = std::max(worst, std::hypot(force[i].x, force[i].y));
    ++checked;
  }
  BOOST_TEST_MESSAGE(checked << " blocks without a sliding contact; their largest force " << worst << " N/m");
  BOOST_TEST(checked >= force.size() / 2);
  // The reported ratio also counts moments and strains, so it bounds the translational part;
  // 1e-9 of F_ref covers the sums' rounding (~100 terms of up to F_ref, 1e-16 each).
  BOOST_TEST(worst / reference <= e.ratio + 1e-9);
}

namespace {

// A column of `count` deformable square blocks of side `side` on the floor, leaning `tilt` rad:
// block k's centre offset by tilt side (k + 1/2).
std::vector<BlockSpec> leaning_column(int count, double side, double tilt) {
  std::vector<BlockSpec> blocks;
  for (int k = 0; k < count; ++k) {
    BlockSpec b = block("c" + std::to_string(k), square(tilt * side * (k + 0.5), side * k, side));
    b.material = rock();
    blocks.push_back(b);
  }
  BlockSpec floor = block("floor", {{-5.0, -1.0}, {7.0, -1.0}, {7.0, 0.0}, {-5.0, 0.0}}, true);
  floor.material = rock();
  blocks.push_back(floor);
  return blocks;
}

// Greenhill's height (4): q h³ = 7.84 EI with EI = 2 kn L⁴ / (12 H), q = rho g L.
double buckling_height(const ContactLaw& law, double side) {
  const double ei = 2.0 * law.normal.kn * std::pow(side, 4) / (12.0 * law.normal.H);
  const double q = rock().density * g * side;
  return std::cbrt(7.84 * ei / q);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_column_above_its_buckling_height_has_no_static_state) {
  BOOST_TEST(std::abs(buckling_height(rock_joints(30.0), 1.0) - 46.2) < 0.1);
  struct Case {
    double side, kn;
  };
  for (const Case& c : {Case{1.0, 2.0e9}, Case{0.5, 2.0e9}, Case{2.0, 2.0e9}, Case{1.0, 2.0e10}}) {
    ContactLaw law = rock_joints(30.0);
    law.normal.kn = c.kn;
    DdaParams params = gravity_params();
    params.dt = 1.0e-4 * std::sqrt(2.0e9 / c.kn);  // the stiffer contacts' critical step
    const double h_cr = buckling_height(law, c.side);
    const int low = static_cast<int>(std::floor(0.85 * h_cr / c.side));
    const int high = static_cast<int>(std::ceil(1.15 * h_cr / c.side));
    BOOST_TEST_CONTEXT("L = " << c.side << " m, kn = " << c.kn << " Pa, h_cr = " << h_cr << " m") {
      {
        const Dda2d sim(leaning_column(low, c.side, 1e-3), law, params);
        const Equilibrium& e = sim.initial_equilibrium();
        BOOST_TEST_MESSAGE(low << " blocks: " << e.iterations << " iterations, ratio " << e.ratio);
        BOOST_TEST(e.converged);
        BOOST_TEST(e.unsettled.empty());
      }
      const std::vector<BlockSpec> blocks = leaning_column(high, c.side, 1e-3);
      const Dda2d sim(blocks, law, params);
      const Equilibrium& e = sim.initial_equilibrium();
      BOOST_TEST_MESSAGE(high << " blocks: " << e.iterations << " iterations, " << e.unsettled.size() << " unsettled");
      BOOST_TEST_REQUIRE(!e.unsettled.empty());
      const auto named = [&](const std::string& id) {
        return std::find(e.unsettled.begin(), e.unsettled.end(), id) != e.unsettled.end();
      };
      BOOST_TEST(named("c" + std::to_string(high - 1)));
      BOOST_TEST(!named("c0"));
      for (std::size_t i = 0; i + 1 < blocks.size(); ++i) {  // the named ones start as given
        if (named(blocks[i].id)) BOOST_TEST((sim.blocks()[i].vertices == blocks[i].vertices));
      }
      if (c.side != 1.0 || c.kn != 2.0e9) continue;
      params.initial_equilibrium = InitialEquilibrium::strict;
      try {
        const Dda2d strict(blocks, law, params);
        BOOST_FAIL("the strict pre-solve took a column above its buckling height");
      } catch (const StabilityError& error) {
        BOOST_TEST_MESSAGE(error.what());
        BOOST_TEST(std::string(error.what()).find("topple or buckle") != std::string::npos);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_mass_with_edge_columns_above_their_buckling_height_settles_without_them) {
  constexpr int width = 8, height = 50;
  const std::vector<BlockSpec> blocks = jointed_mass(width, height);
  const Dda2d sim(blocks, rock_joints(30.0), gravity_params());
  const Equilibrium& e = sim.initial_equilibrium();
  BOOST_TEST_MESSAGE("pre-solve: " << e.iterations << " iterations, ratio " << e.ratio << ", "
                                   << e.unsettled.size() << " unsettled, " << e.seconds << " s");
  BOOST_TEST(e.converged);
  BOOST_TEST(e.ratio < 1e-6);
  BOOST_TEST_REQUIRE(!e.unsettled.empty());
  for (const std::string& id : e.unsettled) {
    const std::string column = id.substr(id.find('_') + 1);
    BOOST_TEST((column == "0" || column == std::to_string(width - 1)), id << " is not in an edge column");
  }
  for (const std::string top : {"b49_0", "b49_7"}) {
    BOOST_TEST((std::find(e.unsettled.begin(), e.unsettled.end(), top) != e.unsettled.end()), top);
  }
  BOOST_TEST(e.blocks == width * height - e.unsettled.size());
}
