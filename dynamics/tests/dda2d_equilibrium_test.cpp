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

#include <cmath>
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

}  // namespace

BOOST_AUTO_TEST_CASE(a_joint_cut_mass_settles_with_its_weight_on_the_floor) {
  constexpr int n = 12;
  std::vector<BlockSpec> blocks;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      BlockSpec b = block("b" + std::to_string(r) + "_" + std::to_string(c), square(c, r, 1.0));
      b.material = rock();
      blocks.push_back(b);
    }
  }
  BlockSpec floor = block("floor", {{-2, -1}, {n + 2, -1}, {n + 2, 0}, {-2, 0}}, true);
  floor.material = rock();
  blocks.push_back(floor);
  DdaParams params;
  params.gravity = {0.0, -g};
  const Dda2d sim(blocks, rock_joints(30.0), params);
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
  DdaParams params;
  params.gravity = {0.0, -g};
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
