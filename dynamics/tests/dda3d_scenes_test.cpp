#define BOOST_TEST_MODULE dynamics_dda3d_scenes
#include <boost/test/unit_test.hpp>

// The seed 001 §6 scenes of examples/scenes3d run on the implicit 3D DDA, checked against what
// mechanics says of them in numbers (the wedge's factor of safety and frictionless slide are in
// safety_factor_test.cpp):
//   §6.2 toppling.json: six slender blocks (b/h = 1.5 / 4 = 0.375 < tan 30°) on a 30° base with
//   φ = 40° (> 30°: none can slide on the base) topple: each turns about its downhill bottom edge
//   while that edge stays where it stood on the base; a squat block (b/h = 4 / 1.5 = 2.67 >
//   tan 30°) on the same base stands.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rockcontact/dynamics/dda3d.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"

namespace dyn = rockcontact::dynamics;
using rockcontact::kernel::Point3;

namespace {

const std::string scenes3d = std::string(ROCKCONTACT_EXAMPLES_DIR) + "/scenes3d/";
constexpr double degrees = 180.0 / std::numbers::pi;

const dyn::Block3dState& block(const dyn::Dda3d& sim, const std::string& id) {
  return *std::find_if(sim.blocks().begin(), sim.blocks().end(), [&](const dyn::Block3dState& b) { return b.id == id; });
}

double distance(const Point3& a, const Point3& b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

}  // namespace

// Toppling (the scene's axes lie along the slope: x down the dip, z normal to the base). The
// criteria in numbers: toppling needs b/h < tan θ (0.375 < 0.577) and sliding tan φ < tan θ
// (0.839 > 0.577: no block slides on its own). After 1 s each slender block has turned by more
// than 5° about the strike (+y, its top downhill) and the squat one by less than 0.5° (the
// issue's bound) and moved less than 1 mm. Turning, not sliding, carries the slender blocks'
// motion: the downhill top edge of each (box vertex 5) has moved at least 10 times as far as its
// downhill bottom edge (vertex 1), about which it turns; a block sliding without turning moves
// both alike. (The bottom edges do slip by a few mm to 5 cm late in the run, under the thrust of
// the row leaning on its downhill end: the docs' validation section gives the numbers.)
BOOST_AUTO_TEST_CASE(slender_blocks_topple_squat_block_stands) {
  const dyn::Scene3d scene = dyn::read_scene3d_file(scenes3d + "toppling.json");
  const double theta = std::atan2(scene.params.gravity[0], -scene.params.gravity[2]);
  BOOST_TEST(std::fabs(theta * degrees - 30.0) < 1e-9);
  BOOST_TEST(1.5 / 4.0 < std::tan(theta));
  BOOST_TEST(std::tan(scene.law.interfaces.at(0).friction_angle_deg / degrees) > std::tan(theta));
  dyn::Dda3d sim(scene.blocks, scene.law, scene.params);
  std::vector<Point3> bottoms, tops;
  for (int k = 1; k <= 6; ++k) {
    bottoms.push_back(block(sim, "t" + std::to_string(k)).parts[0][1]);
    tops.push_back(block(sim, "t" + std::to_string(k)).parts[0][5]);
  }
  const Point3 squat0 = block(sim, "squat").centroid;
  while (sim.time() < 1.0 - 1e-9) sim.step();
  for (int k = 1; k <= 6; ++k) {
    const dyn::Block3dState& b = block(sim, "t" + std::to_string(k));
    const auto i = static_cast<std::size_t>(k - 1);
    const double turned = b.rotation[1] * degrees;
    const double bottom = distance(b.parts[0][1], bottoms[i]), top = distance(b.parts[0][5], tops[i]);
    BOOST_TEST_MESSAGE("t" << k << ": turned " << turned << "°, top edge moved " << top << " m, bottom edge " << bottom
                           << " m");
    BOOST_TEST(turned > 5.0);
    BOOST_TEST(top > 10.0 * bottom);
  }
  const dyn::Block3dState& squat = block(sim, "squat");
  const double squat_turn = std::hypot(squat.rotation[0], squat.rotation[1], squat.rotation[2]) * degrees;
  BOOST_TEST_MESSAGE("squat: turned " << squat_turn << "°, moved " << distance(squat.centroid, squat0) << " m");
  BOOST_TEST(squat_turn < 0.5);
  BOOST_TEST(distance(squat.centroid, squat0) < 1e-3);
}

// Seed 001 §6.1, Table 4: the wedge rests on its base with six contact constraints at four
// positions: one at each of its two front top corners, on the joint that corner lies on, and
// two at the crest and at the daylight point, which lie on the line of intersection, one per
// joint. The base is three convex parts and the wedge's corners are corners of the base too, so
// each position is found from several part pairs and from both blocks' vertices; it is one
// constraint all the same (contact_constraints.hpp, step 5), after the initial equilibrium and
// after the wedge has started to move (the corners drift apart by the settling). Counted on the
// closed constraints, by position (1 cm apart at least) and joint (the two normals 61° apart).
BOOST_AUTO_TEST_CASE(wedge_has_table_4s_six_constraints) {
  const dyn::Scene3d scene = dyn::read_scene3d_file(scenes3d + "wedge.json");
  dyn::Dda3d sim(scene.blocks, scene.law, scene.params);
  for (int step = 0; step <= 20; step += 20) {
    while (static_cast<int>(sim.steps()) < step) sim.step();
    std::vector<dyn::Contact3dState> closed;
    for (const dyn::Contact3dState& c : sim.contacts()) {
      if (c.mode != dyn::ContactMode3d::open) closed.push_back(c);
    }
    BOOST_TEST_CONTEXT("after " << step << " steps") {
      BOOST_TEST(closed.size() == 6u);
      std::vector<Point3> positions;
      for (const dyn::Contact3dState& c : closed) {
        if (std::none_of(positions.begin(), positions.end(), [&](const Point3& p) { return distance(p, c.point) < 0.01; })) {
          positions.push_back(c.point);
        }
      }
      BOOST_TEST(positions.size() == 4u);
    }
  }
}
