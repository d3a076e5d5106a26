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
// (3) A mass the pre-solve does not settle: 8 x 50 blocks as in (1), whose edge columns stand
//     taller than such a column can alone (docs/performance.md, "The 2D initial equilibrium").
//     "auto" starts the run from the least out-of-balance state it reported on the way (its
//     progress reports every Newton iteration and every 100th of the relaxation), not from
//     where the relaxation gave up; and that state's translational balance, recomputed here
//     from the blocks' weights and the contact forces, is within the ratio it reports.

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

BOOST_AUTO_TEST_CASE(a_mass_that_does_not_settle_starts_from_its_least_out_of_balance_state) {
  const std::vector<BlockSpec> blocks = jointed_mass(8, 50);
  DdaParams params;
  params.gravity = {0.0, -g};
  double least = std::numeric_limits<double>::infinity();
  params.equilibrium_progress = [&](std::size_t, double ratio) { least = std::min(least, ratio); };
  const Dda2d sim(blocks, rock_joints(30.0), params);
  const Equilibrium& e = sim.initial_equilibrium();
  BOOST_TEST_MESSAGE("pre-solve: " << e.iterations << " iterations, ratio " << e.ratio << ", least reported "
                                   << least << ", " << e.seconds << " s");
  BOOST_TEST_REQUIRE(!e.converged);  // the case this test is about (when it settles, see (1))
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
