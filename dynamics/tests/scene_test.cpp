#define BOOST_TEST_MODULE scene
#include "rockcontact/dynamics/io/scene.hpp"

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"
#include "rockcontact/testing/input_error.hpp"

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;
namespace contact = rockcontact::contact;
using nlohmann::json;

namespace {

const std::string scene_dir = ROCKCONTACT_DYNAMICS_TESTDATA_DIR "/scenes";

// The scene of the run contract (dynamics/tests/data/scenes/two_blocks.json, inline).
json contract_scene() {
  return json::parse(R"({"dimension": 2,
   "time": {"dt": 1e-4, "duration": 1.0},
   "gravity": [0, -9.81],
   "materials": {"rock": {"density": 2000, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e7, "kt": 1e7, "friction_angle_deg": 10,
               "H": 1.0, "policy": "filtered", "demarcation": "exact"},
   "blocks": [{"id": "base", "material": "rock", "vertices": [[0,0],[4,0],[4,1],[0,1]],
               "fixed": true},
              {"id": "slider", "material": "rock", "vertices": [[1,1],[2,1],[2,2],[1,2]],
               "velocity": [0.5, -0.25, 0.125], "rigid": false}],
   "output": {"track": ["slider"], "every": 100}})");
}

// The smallest scene: what is left when every optional field is dropped.
json minimal_scene() {
  return json::parse(R"({"dimension": 2,
   "time": {"dt": 1e-3, "duration": 0.5},
   "materials": {"soft": {"density": 1500, "youngs_modulus": 2e8, "poisson_ratio": 0.3}},
   "contact": {"law": "potential", "kn": 5e7, "H": "mean_edge"},
   "blocks": [{"id": "ground", "material": "soft", "vertices": [[0,0],[4,0],[4,1],[0,1]],
               "fixed": true},
              {"id": "a", "material": "soft", "vertices": [[1,1],[2,1],[2,2],[1,2]]},
              {"id": "b", "material": "soft", "vertices": [[3,1],[4,1],[3.5,2]]}]})");
}

// `change` applied to the contract scene must be rejected with an error naming the source, the
// JSON path and containing `expected`.
void expect_error(const std::function<void(json&)>& change, const std::string& path,
                  const std::string& expected) {
  json document = contract_scene();
  change(document);
  rockcontact::testing::expect_input_error(&dyn::parse_scene, document, path, expected);
}

std::optional<dyn::InputError> file_error(const std::string& file) {
  try {
    dyn::read_scene_file(file);
  } catch (const dyn::InputError& e) {
    BOOST_TEST_MESSAGE(e.what());
    return e;
  }
  return std::nullopt;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_CASE(contract_scene_maps_onto_the_engine_specs) {
  const dyn::Scene scene = dyn::parse_scene(contract_scene(), "contract.json");
  BOOST_TEST(scene.source == "contract.json");
  BOOST_TEST(scene.params.dt == 1e-4);
  BOOST_TEST(scene.duration == 1.0);
  BOOST_TEST(scene.params.gravity.x == 0.0);
  BOOST_TEST(scene.params.gravity.y == -9.81);
  BOOST_TEST((scene.params.plane == dyn::PlaneMode::stress));
  BOOST_TEST(scene.params.mass_damping == 0.0);

  BOOST_TEST(scene.law.normal.kn == 1e7);
  BOOST_TEST(scene.law.normal.H == 1.0);
  BOOST_TEST((scene.h_rule == dyn::HRule::given));
  BOOST_TEST((scene.law.normal.demarcation == kernel::Demarcation::exact));
  BOOST_TEST((scene.law.policy == kernel::PolicyKind::filtered));
  BOOST_TEST_REQUIRE(scene.law.friction.has_value());
  BOOST_TEST(scene.law.friction->kt == 1e7);
  BOOST_TEST(scene.law.friction->friction_angle_deg == 10.0);

  BOOST_TEST_REQUIRE(scene.blocks.size() == 2u);
  const dyn::BlockSpec& base = scene.blocks[0];
  const dyn::BlockSpec& slider = scene.blocks[1];
  BOOST_TEST(base.id == "base");
  BOOST_TEST(base.fixed);
  BOOST_TEST(!base.rigid);
  BOOST_TEST(base.vertices.size() == 4u);
  BOOST_TEST(slider.id == "slider");
  BOOST_TEST(!slider.fixed);
  BOOST_TEST(!slider.rigid);
  BOOST_TEST((slider.vertices[2] == kernel::Point2{2, 2}));
  BOOST_TEST(slider.material.density == 2000.0);
  BOOST_TEST(slider.material.youngs_modulus == 1e9);
  BOOST_TEST(slider.material.poisson_ratio == 0.25);
  BOOST_TEST(slider.velocity.x == 0.5);
  BOOST_TEST(slider.velocity.y == -0.25);
  BOOST_TEST(slider.omega == 0.125);

  BOOST_TEST(scene.track == std::vector<std::string>{"slider"});
  BOOST_TEST(scene.every == 100u);
  BOOST_TEST(dyn::step_count(scene) == 10000u);
}

BOOST_AUTO_TEST_CASE(optional_fields_take_their_documented_defaults) {
  json document = minimal_scene();
  const dyn::Scene scene = dyn::parse_scene(document, "minimal.json");
  BOOST_TEST(scene.params.gravity.y == -9.81);
  BOOST_TEST((scene.params.plane == dyn::PlaneMode::stress));
  BOOST_TEST(scene.params.mass_damping == 0.0);
  BOOST_TEST(!scene.law.friction.has_value());  // no kt, no friction angle: frictionless
  BOOST_TEST((scene.law.policy == kernel::PolicyKind::filtered));
  BOOST_TEST((scene.law.normal.demarcation == kernel::Demarcation::exact));
  BOOST_TEST(scene.track == (std::vector<std::string>{"a", "b"}));  // every block not fixed
  BOOST_TEST(scene.every == 100u);
  BOOST_TEST(!scene.blocks[1].fixed);
  BOOST_TEST(scene.blocks[1].velocity.x == 0.0);
  BOOST_TEST((scene.params.initial_equilibrium == dyn::InitialEquilibrium::automatic));
  BOOST_TEST(scene.law.damping_ratio == 0.0);
  BOOST_TEST((scene.params.analysis == dyn::Analysis::dynamic));
  BOOST_TEST(scene.static_tolerance == 1e-6);

  document["plane"] = "strain";
  document["damping"] = 0.5;
  document["gravity"] = {0, 0};
  document["blocks"][1]["rigid"] = true;
  document["contact"]["policy"] = "exact";
  document["contact"]["demarcation"] = "paper";
  document["output"] = {{"every", 7}};
  const dyn::Scene changed = dyn::parse_scene(document, "minimal.json");
  BOOST_TEST((changed.params.plane == dyn::PlaneMode::strain));
  BOOST_TEST(changed.params.mass_damping == 0.5);
  BOOST_TEST(changed.params.gravity.y == 0.0);
  BOOST_TEST(changed.blocks[1].rigid);
  BOOST_TEST((changed.law.policy == kernel::PolicyKind::exact));
  BOOST_TEST((changed.law.normal.demarcation == kernel::Demarcation::paper));
  BOOST_TEST(changed.every == 7u);
  BOOST_TEST(changed.track == (std::vector<std::string>{"a", "b"}));
}

// Hand values: ground 4 x 1 (edges 4, 1, 4, 1), a 1 x 1 (4 x 1), b the triangle (3,1) (4,1)
// (3.5,2) with edges 1, sqrt(1.25), sqrt(1.25): mean = (14 + 1 + 2 sqrt(1.25)) / 11.
BOOST_AUTO_TEST_CASE(mean_edge_H_is_the_mean_of_all_edges) {
  const dyn::Scene scene = dyn::parse_scene(minimal_scene(), "minimal.json");
  BOOST_TEST((scene.h_rule == dyn::HRule::mean_edge));
  const double hand = (14.0 + 1.0 + 2.0 * std::sqrt(1.25)) / 11.0;
  BOOST_TEST(scene.law.normal.H == hand, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(dyn::mean_edge_length(scene.blocks) == hand, boost::test_tools::tolerance(1e-15));
}

// The same over the blocks that move, a and b (the fixed ground's 4 m edges left out):
// (4 + 1 + 2 sqrt(1.25)) / 7. Growing the ground leaves it unchanged.
BOOST_AUTO_TEST_CASE(mean_edge_movable_H_leaves_the_fixed_blocks_out) {
  json document = minimal_scene();
  document["contact"]["H"] = "mean_edge_movable";
  const double hand = (5.0 + 2.0 * std::sqrt(1.25)) / 7.0;
  const dyn::Scene scene = dyn::parse_scene(document, "minimal.json");
  BOOST_TEST((scene.h_rule == dyn::HRule::mean_edge_movable));
  BOOST_TEST(scene.law.normal.H == hand, boost::test_tools::tolerance(1e-15));
  document["blocks"][0]["vertices"] = json::parse("[[-40, -9], [44, -9], [44, 1], [-40, 1]]");
  BOOST_TEST(dyn::parse_scene(document, "minimal.json").law.normal.H == hand,
             boost::test_tools::tolerance(1e-15));
  for (json& block : document["blocks"]) block["fixed"] = true;
  BOOST_CHECK_EXCEPTION(dyn::parse_scene(document, "minimal.json"), dyn::InputError,
                        [](const dyn::InputError& e) {
                          return e.path() == "contact.H" &&
                                 std::string(e.what()).find("needs a block that is not fixed") !=
                                     std::string::npos;
                        });
}

// Hand values: the triangle b has sides 1, sqrt(1.25), sqrt(1.25) and area 0.5, so its inradius
// is area / semi-perimeter = 0.5 / (0.5 + sqrt(1.25)); the squares' is 0.5 and the ground's 0.5.
BOOST_AUTO_TEST_CASE(inscribed_H_is_the_smallest_inscribed_radius) {
  json document = minimal_scene();
  document["contact"]["H"] = "inscribed";
  const dyn::Scene scene = dyn::parse_scene(document, "minimal.json");
  BOOST_TEST((scene.h_rule == dyn::HRule::inscribed));
  const double hand = 0.5 / (0.5 + std::sqrt(1.25));
  BOOST_TEST(scene.law.normal.H == hand, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(step_count_rounds_up_but_not_for_decimal_noise) {
  dyn::Scene scene;
  scene.params.dt = 1e-4;
  scene.duration = 1.0;
  BOOST_TEST(dyn::step_count(scene) == 10000u);
  scene.params.dt = 2e-5;
  scene.duration = 0.2;
  BOOST_TEST(dyn::step_count(scene) == 10000u);
  scene.params.dt = 0.1;
  scene.duration = 0.25;
  BOOST_TEST(dyn::step_count(scene) == 3u);
}

BOOST_AUTO_TEST_CASE(top_level_errors) {
  expect_error([](json& d) { d["dimension"] = 3; }, "dimension", "a 3D scene, read by parse_scene3d");
  expect_error([](json& d) { d["format"] = "rockcontact-scene/2"; }, "format",
               "the scene is written in format rockcontact-scene/2; this rockcontact reads "
               "rockcontact-scene/1");
  expect_error([](json& d) { d["format"] = 1; }, "format",
               R"(expected "rockcontact-scene/1", got number 1)");
  expect_error([](json& d) { d["dimension"] = "2"; }, "dimension", "expected 2, got string");
  expect_error([](json& d) { d.erase("dimension"); }, "dimension", "missing field");
  expect_error([](json& d) { d["colour"] = "red"; }, "colour",
               "unknown field; expected only format, description, dimension, time");
  expect_error([](json& d) { d.erase("time"); }, "time", "missing field");
  expect_error([](json& d) { d["time"]["dt"] = -1e-4; }, "time.dt",
               "expected the time step in s, a finite number > 0, got number -0.0001");
  expect_error([](json& d) { d["time"]["duration"] = "1 s"; }, "time.duration",
               "a finite number > 0");
  expect_error([](json& d) { d["time"]["steps"] = 10; }, "time.steps", "unknown field");
  expect_error([](json& d) { d["gravity"] = {0, -9.81, 0}; }, "gravity", "two finite numbers");
  expect_error([](json& d) { d["gravity"] = {0, "down"}; }, "gravity[1]", "a finite number");
  expect_error([](json& d) { d["plane"] = "axisymmetric"; }, "plane",
               R"(one of "stress", "strain")");
  expect_error([](json& d) { d["damping"] = -0.1; }, "damping", "a finite number >= 0");
}

BOOST_AUTO_TEST_CASE(material_and_contact_errors) {
  expect_error([](json& d) { d["materials"] = json::array(); }, "materials", "expected an object");
  expect_error([](json& d) { d["materials"]["rock"]["cohesion"] = 1e5; }, "materials.rock.cohesion",
               "unknown field");
  expect_error([](json& d) { d["materials"]["rock"].erase("density"); }, "materials.rock.density",
               "missing field");
  expect_error([](json& d) { d["materials"]["rock"]["poisson_ratio"] = 0.5; },
               "materials.rock.poisson_ratio", "a number in (-1, 0.5)");
  expect_error([](json& d) { d["materials"]["rock"]["poisson_ratio"] = -1; },
               "materials.rock.poisson_ratio", "a number in (-1, 0.5)");
  expect_error([](json& d) { d["contact"]["law"] = "coulomb"; }, "contact.law",
               R"(expected "potential")");
  expect_error([](json& d) { d["contact"]["kn"] = 0; }, "contact.kn", "a finite number > 0");
  expect_error([](json& d) { d["contact"]["H"] = "median"; }, "contact.H",
               R"(a length in m > 0, "mean_edge", "mean_edge_movable" or "inscribed", got string "median")");
  expect_error([](json& d) { d["contact"]["H"] = -1.0; }, "contact.H", "a length in m > 0");
  expect_error([](json& d) { d["contact"].erase("friction_angle_deg"); },
               "contact.friction_angle_deg", "kt and friction_angle_deg come together");
  expect_error([](json& d) { d["contact"].erase("kt"); }, "contact.kt",
               "kt and friction_angle_deg come together");
  expect_error([](json& d) { d["contact"]["friction_angle_deg"] = 90; },
               "contact.friction_angle_deg", "a number in [0, 90)");
  expect_error([](json& d) { d["contact"]["policy"] = "fast"; }, "contact.policy",
               R"(one of "float", "filtered", "exact", "checked")");
  expect_error([](json& d) { d["contact"]["mu"] = 0.3; }, "contact.mu", "unknown field");
  expect_error([](json& d) { d["contact"]["friction"] = "coulomb"; }, "contact.friction",
               R"(one of "elastoplastic", "paper" (with kt and friction_angle_deg), got string "coulomb")");
  expect_error([](json& d) { d["contact"]["cohesion"] = -1.0; }, "contact.cohesion",
               "the cohesion in Pa, a finite number >= 0");
  expect_error([](json& d) { d["contact"]["damping_ratio"] = -0.1; }, "contact.damping_ratio",
               "the contact dashpots' critical damping ratio, a finite number >= 0");
  expect_error([](json& d) { d["initial_equilibrium"] = "yes"; }, "initial_equilibrium",
               R"("auto", true or false)");
  expect_error([](json& d) { d["analysis"] = "quasi-static"; }, "analysis",
               R"(one of "dynamic", "static", got string "quasi-static")");
  expect_error([](json& d) { d["static_tolerance"] = 0.0; }, "static_tolerance",
               "a number in (0, 1)");
  expect_error([](json& d) { d["static_tolerance"] = 1.0; }, "static_tolerance",
               "a number in (0, 1)");
  expect_error(
      [](json& d) {
        d["contact"].erase("kt");
        d["contact"].erase("friction_angle_deg");
        d["contact"]["friction"] = "paper";
      },
      "contact.friction", "a friction parameter of frictionless contact");
}

// The friction law, cohesion, contact damping, the pre-solve switch and the static analysis as
// the scene gives them;
// the law defaults to elastoplastic, and an interface takes its own cohesion or the scene's.
BOOST_AUTO_TEST_CASE(friction_law_cohesion_and_damping_fields) {
  json document = contract_scene();
  BOOST_TEST((dyn::parse_scene(document, "c.json").law.friction->model ==
              contact::FrictionModel::elastoplastic));
  document["contact"]["friction"] = "paper";
  document["contact"]["cohesion"] = 2.5e4;
  document["contact"]["damping_ratio"] = 0.1;
  document["initial_equilibrium"] = false;
  document["analysis"] = "static";
  document["static_tolerance"] = 1e-4;
  document["blocks"][0]["group"] = "base";
  document["interfaces"] = json::parse(R"([{"between": ["base", "base"], "cohesion": 1e3}])");
  const dyn::Scene scene = dyn::parse_scene(document, "c.json");
  BOOST_TEST((scene.law.friction->model == contact::FrictionModel::paper));
  BOOST_TEST(scene.law.friction->cohesion == 2.5e4);
  BOOST_TEST(scene.law.damping_ratio == 0.1);
  BOOST_TEST((scene.params.initial_equilibrium == dyn::InitialEquilibrium::off));
  BOOST_TEST((scene.params.analysis == dyn::Analysis::static_equilibrium));
  BOOST_TEST(scene.static_tolerance == 1e-4);
  BOOST_TEST_REQUIRE(scene.law.interfaces.size() == 1u);
  BOOST_TEST(scene.law.interfaces[0].friction->cohesion == 1e3);
  BOOST_TEST(scene.law.interfaces[0].friction->friction_angle_deg == 10.0);
  BOOST_TEST((scene.law.interfaces[0].friction->model == contact::FrictionModel::paper));
}

BOOST_AUTO_TEST_CASE(block_errors) {
  expect_error([](json& d) { d["blocks"] = json::array(); }, "blocks",
               R"(the scene has no blocks; expected "blocks" or a "region")");
  expect_error([](json& d) { d["blocks"] = json::object(); }, "blocks", "an array of blocks");
  expect_error([](json& d) { d["blocks"][1]["colour"] = "red"; }, "blocks[1].colour",
               "unknown field; expected only id, material, vertices, fixed, rigid, velocity, group");
  expect_error([](json& d) { d["blocks"][1].erase("vertices"); }, "blocks[1].vertices",
               "missing field");
  expect_error([](json& d) { d["blocks"][1]["vertices"][2] = {2}; }, "blocks[1].vertices[2]",
               "expected a vertex, an [x, y] pair of numbers, got array [2]");
  expect_error([](json& d) { d["blocks"][1]["id"] = "base"; }, "blocks[1].id",
               R"(duplicate id "base" (also blocks[0].id))");
  expect_error([](json& d) { d["blocks"][1]["id"] = ""; }, "blocks[1].id", "a non-empty string");
  expect_error([](json& d) { d["blocks"][1]["material"] = "granite"; }, "blocks[1].material",
               R"(unknown material "granite"; expected one of the scene's materials (rock))");
  expect_error([](json& d) { d["blocks"][1]["fixed"] = "yes"; }, "blocks[1].fixed",
               "expected true or false");
  expect_error(
      [](json& d) {
        d["blocks"][1]["velocity"] = {1, 0};
      },
      "blocks[1].velocity", "[vx, vy, omega]");
  expect_error(
      [](json& d) {
        d["blocks"][0]["velocity"] = {1, 0, 0};
      },
      "blocks[0].velocity", "a fixed block does not move");
}

// Polygon errors come from the kernel's validation: the message names the block id and the
// vertex, the path the vertex (or the polygon, for whole-polygon problems).
BOOST_AUTO_TEST_CASE(polygon_errors_name_the_block) {
  expect_error(
      [](json& d) {
        d["blocks"][1]["vertices"] = {{1, 1}, {1.5, 1}, {2, 1}, {2, 2}};
      },
      "blocks[1].vertices[1]", "polygon block 'slider', vertex 1: is collinear");
  expect_error(
      [](json& d) {
        d["blocks"][1]["vertices"] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
      },
      "blocks[1].vertices", "block 'slider'");
  expect_error(
      [](json& d) {
        d["blocks"][1]["vertices"] = {{1, 1}, {2, 1}};
      },
      "blocks[1].vertices", "needs at least 3 vertices");
  expect_error(
      [](json& d) {
        d["blocks"][1]["vertices"] = {{1, 1}, {2, 1}, {2, 1}, {1, 2}};
      },
      "blocks[1].vertices[2]", "repeats vertex 1");
}

BOOST_AUTO_TEST_CASE(output_errors) {
  expect_error(
      [](json& d) {
        d["output"]["track"] = {"slider", "ghost"};
      },
      "output.track[1]", R"(no block has the id "ghost")");
  expect_error(
      [](json& d) {
        d["output"]["track"] = {"slider", "slider"};
      },
      "output.track[1]", "listed twice");
  expect_error([](json& d) { d["output"]["track"] = "slider"; }, "output.track",
               "an array of block ids");
  expect_error([](json& d) { d["output"]["every"] = 0; }, "output.every", "an integer >= 1");
  expect_error([](json& d) { d["output"]["every"] = 2.5; }, "output.every", "an integer >= 1");
  expect_error([](json& d) { d["output"]["format"] = "csv"; }, "output.format", "unknown field");
}

BOOST_AUTO_TEST_CASE(file_errors_name_the_file) {
  const auto bad_vertex = file_error(scene_dir + "/slider.json");
  BOOST_TEST_REQUIRE(bad_vertex.has_value());
  BOOST_TEST(bad_vertex->path() == "blocks[1].vertices[2]");
  BOOST_TEST(contains(bad_vertex->what(), "slider.json: blocks[1].vertices[2]: expected a vertex"));

  const auto collinear = file_error(scene_dir + "/collinear.json");
  BOOST_TEST_REQUIRE(collinear.has_value());
  BOOST_TEST(contains(collinear->what(),
                      "collinear.json: blocks[1].vertices[1]: polygon block "
                      "'slider', vertex 1: is collinear"));

  const auto three_d = file_error(scene_dir + "/three_d.json");
  BOOST_TEST_REQUIRE(three_d.has_value());
  BOOST_TEST(contains(three_d->what(), "three_d.json: dimension: a 3D scene, read by parse_scene3d"));

  const auto missing = file_error(scene_dir + "/no_such_scene.json");
  BOOST_TEST_REQUIRE(missing.has_value());
  BOOST_TEST(contains(missing->what(), "no_such_scene.json: cannot open"));

  BOOST_TEST(!file_error(scene_dir + "/two_blocks.json").has_value());
}

// A boundary segment (seed 000 §3.3) is the edge from -> to of a fixed rectangle on its right.
// Hand values: the floor from (4, 0) to (-2, 0) runs leftwards, so its rectangle lies above it,
// depth 0.5: (4, 0.5), (-2, 0.5), (-2, 0), (4, 0) in CCW order; the wall from (0, 0) to (0, 3)
// with the default depth |to - from| = 3 lies at x in [0, 3]. H (mean_edge) still counts the
// blocks only, and the default track list still skips fixed blocks.
BOOST_AUTO_TEST_CASE(boundary_segments_become_fixed_rectangles_on_their_right) {
  json document = minimal_scene();
  document["boundaries"] = json::parse(R"([
    {"id": "floor", "material": "soft", "from": [4, 0], "to": [-2, 0], "depth": 0.5},
    {"id": "wall", "material": "soft", "from": [0, 0], "to": [0, 3]}])");
  const dyn::Scene scene = dyn::parse_scene(document, "boundaries.json");
  BOOST_TEST_REQUIRE(scene.blocks.size() == 5u);
  const dyn::BlockSpec& floor = scene.blocks[3];
  const dyn::BlockSpec& wall = scene.blocks[4];
  BOOST_TEST(floor.id == "floor");
  BOOST_TEST(floor.fixed);
  const std::vector<kernel::Point2> floor_hand{{4, 0.5}, {-2, 0.5}, {-2, 0}, {4, 0}};
  const std::vector<kernel::Point2> wall_hand{{3, 0}, {3, 3}, {0, 3}, {0, 0}};
  BOOST_TEST_REQUIRE(floor.vertices.size() == 4u);
  BOOST_TEST_REQUIRE(wall.vertices.size() == 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    BOOST_TEST_CONTEXT("vertex " << k) {  // exact: the offsets are exact multiples here
      BOOST_TEST(floor.vertices[k].x == floor_hand[k].x);
      BOOST_TEST(floor.vertices[k].y == floor_hand[k].y);
      BOOST_TEST(wall.vertices[k].x == wall_hand[k].x);
      BOOST_TEST(wall.vertices[k].y == wall_hand[k].y);
    }
  }
  const double hand_h = (14.0 + 1.0 + 2.0 * std::sqrt(1.25)) / 11.0;  // as without boundaries
  BOOST_TEST(scene.law.normal.H == hand_h, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(scene.track == (std::vector<std::string>{"a", "b"}));
}

BOOST_AUTO_TEST_CASE(boundary_errors) {
  const auto with_boundary = [](const char* text) {
    return [text](json& d) { d["boundaries"] = json::array({json::parse(text)}); };
  };
  expect_error([](json& d) { d["boundaries"] = json::object(); }, "boundaries",
               "an array of boundary segments");
  expect_error(with_boundary(R"({"id": "floor", "material": "rock", "from": [0, 0]})"),
               "boundaries[0].to", "missing field");
  expect_error(with_boundary(R"({"id": "floor", "material": "rock", "from": [0, 0],
                                 "to": [1, 0], "side": "left"})"),
               "boundaries[0].side", "unknown field; expected only id, material, from, to, depth");
  expect_error(with_boundary(R"({"id": "floor", "material": "rock", "from": [1, 2], "to": [1, 2]})"),
               "boundaries[0].to", "to equals from");
  expect_error(with_boundary(R"({"id": "floor", "material": "rock", "from": [0, 0], "to": [1, 0],
                                 "depth": -1})"),
               "boundaries[0].depth", "a finite number > 0");
  expect_error(with_boundary(R"({"id": "base", "material": "rock", "from": [0, 0], "to": [1, 0]})"),
               "boundaries[0].id", R"(duplicate id "base")");
  expect_error(with_boundary(R"({"id": "floor", "material": "clay", "from": [0, 0], "to": [1, 0]})"),
               "boundaries[0].material", R"(unknown material "clay")");
}

// A rigid 1 m square resting on a floor segment: the contact must hold it at its static
// penetration. Face on face over L = 1 m, the potential force is 2 kn L δ / H (both long edges
// of the thin IP count, dda2d.hpp), so δ = m g H / (2 kn L) = 2000 · 9.81 · 1 / (2e7) =
// 0.981 mm. Starting at rest exactly that deep, the block must stay there: its centroid moves by
// less than 1e-3 δ over 0.05 s (the normal force matches the weight to the rounding of δ and of
// the IP construction, both ~1e-16 relative, so any drift at all would come from a contact that
// does not act through the boundary).
BOOST_AUTO_TEST_CASE(block_rests_on_a_floor_segment_at_its_static_penetration) {
  const double delta = 2000.0 * 9.81 * 1.0 / (2.0 * 1e7 * 1.0);
  json document = json::parse(R"({"dimension": 2,
   "time": {"dt": 1e-4, "duration": 0.05},
   "materials": {"rock": {"density": 2000, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e7, "H": 1.0},
   "boundaries": [{"id": "floor", "material": "rock", "from": [-3, 0], "to": [3, 0]}]})");
  document["blocks"] = json::array({{{"id", "block"},
                                     {"material", "rock"},
                                     {"rigid", true},
                                     {"vertices", {{-0.5, -delta}, {0.5, -delta}, {0.5, 1 - delta},
                                                   {-0.5, 1 - delta}}}}});
  const dyn::Scene scene = dyn::parse_scene(document, "resting.json");
  dyn::Dda2d sim(scene.blocks, scene.law, scene.params);
  const kernel::Point2 start = sim.blocks()[0].centroid;
  while (sim.steps() < dyn::step_count(scene)) sim.step();
  const kernel::Point2 end = sim.blocks()[0].centroid;
  BOOST_TEST(sim.contacts().size() == 1u);
  BOOST_TEST(std::hypot(end.x - start.x, end.y - start.y) <= 1e-3 * delta);
}

// A region cut by two joint sets (kernel/block_cutting.hpp): the 10 m square [0, 10]² with
// traces every 2.5 m at 0° and 90° gives 16 squares of 2.5 m, named "<id_prefix>_<k>", in the
// region's material and group, after the explicit blocks; every edge is 2.5 m, so the mean-edge
// H of the generated blocks alone is 2.5 m (the explicit block below has edges of 1 m and
// moves the mean to (16·4·2.5 + 4·1) / 68).
BOOST_AUTO_TEST_CASE(region_is_cut_by_the_joint_sets) {
  json document = minimal_scene();
  document["blocks"] = json::array({document["blocks"][1]});
  document["region"] = json::parse(R"({"vertices": [[0, 2], [10, 2], [10, 12], [0, 12]],
                                       "material": "soft", "group": "rock", "id_prefix": "r"})");
  document["joint_sets"] = json::parse(R"([{"dip_deg": 0, "spacing": 2.5, "offset": 2},
                                           {"dip_deg": 90, "spacing": 2.5}])");
  const dyn::Scene scene = dyn::parse_scene(document, "region.json");
  BOOST_TEST_REQUIRE(scene.blocks.size() == 17u);
  BOOST_TEST(scene.generated_first == 1u);
  BOOST_TEST(scene.generated_count == 16u);
  double area = 0.0;
  for (std::size_t i = 1; i < 17; ++i) {
    const dyn::BlockSpec& b = scene.blocks[i];
    BOOST_TEST(b.id == "r_" + std::to_string(i));
    BOOST_TEST(b.group == "rock");
    BOOST_TEST(scene.material_names[i] == "soft");
    BOOST_TEST(b.vertices.size() == 4u);
    area += rockcontact::kernel::polygon_area(b.vertices);
  }
  BOOST_TEST(area == 100.0);  // 16 exact squares of 6.25 m²
  BOOST_TEST(scene.law.normal.H == (16.0 * 4.0 * 2.5 + 4.0) / 68.0, boost::test_tools::tolerance(1e-15));

  // `rockcontact cut` output: the generated blocks in the scene format, which read back as the
  // same blocks when pasted into "blocks".
  const nlohmann::ordered_json cut = dyn::generated_blocks_json(scene);
  BOOST_TEST_REQUIRE(cut.at("blocks").size() == 16u);
  json pasted = minimal_scene();
  pasted["blocks"] = json::parse(cut.dump()).at("blocks");
  const dyn::Scene again = dyn::parse_scene(pasted, "pasted.json");
  for (std::size_t i = 0; i < 16; ++i) {
    BOOST_TEST(again.blocks[i].id == scene.blocks[i + 1].id);
    BOOST_TEST(again.blocks[i].group == "rock");
    for (std::size_t k = 0; k < 4; ++k) {
      BOOST_TEST(again.blocks[i].vertices[k].x == scene.blocks[i + 1].vertices[k].x);
      BOOST_TEST(again.blocks[i].vertices[k].y == scene.blocks[i + 1].vertices[k].y);
    }
  }
}

// A non-convex block (an L) is accepted as it is (the engine splits it); one that is not simple
// is an error naming the block and the vertices path.
BOOST_AUTO_TEST_CASE(non_convex_blocks_are_accepted_when_simple) {
  json document = contract_scene();
  document["blocks"][1]["vertices"] = json::parse("[[1,1],[3,1],[3,2],[2,2],[2,3],[1,3]]");
  const dyn::Scene scene = dyn::parse_scene(document, "l.json");
  BOOST_TEST(scene.blocks[1].vertices.size() == 6u);
  expect_error([](json& d) { d["blocks"][1]["vertices"] = json::parse("[[1,1],[3,3],[3,1],[1,3]]"); },
               "blocks[1].vertices", "block 'slider' is not convex, and not a simple CCW polygon either");
}

// Interfaces take what they leave out from "contact".
BOOST_AUTO_TEST_CASE(interfaces_fall_back_on_the_contact_defaults) {
  json document = contract_scene();
  document["blocks"][0]["group"] = "boundary";
  document["blocks"][1]["group"] = "rock";
  document["interfaces"] = json::parse(R"([{"between": ["rock", "boundary"], "friction_angle_deg": 35},
                                           {"between": ["rock", "rock"], "kn": 2e7, "kt": 5e6}])");
  const dyn::Scene scene = dyn::parse_scene(document, "interfaces.json");
  BOOST_TEST_REQUIRE(scene.law.interfaces.size() == 2u);
  const dyn::Interface& a = scene.law.interfaces[0];
  const dyn::Interface& b = scene.law.interfaces[1];
  BOOST_TEST((a.groups == std::array<std::string, 2>{"rock", "boundary"}));
  BOOST_TEST(a.kn == 1e7);
  BOOST_TEST_REQUIRE(a.friction.has_value());
  BOOST_TEST(a.friction->kt == 1e7);
  BOOST_TEST(a.friction->friction_angle_deg == 35.0);
  BOOST_TEST(b.kn == 2e7);
  BOOST_TEST_REQUIRE(b.friction.has_value());
  BOOST_TEST(b.friction->kt == 5e6);
  BOOST_TEST(b.friction->friction_angle_deg == 10.0);
}

BOOST_AUTO_TEST_CASE(region_joint_set_and_interface_errors) {
  const auto with = [](const char* field, const char* text) {
    return [field, text](json& d) { d[field] = json::parse(text); };
  };
  expect_error(with("joint_sets", R"([{"dip_deg": 0, "spacing": 1}])"), "joint_sets",
               R"(joint sets cut a region; expected a "region" beside them)");
  expect_error(with("region", R"({"vertices": [[0,0],[0,1],[1,1],[1,0]], "material": "rock"})"),
               "region.vertices", "clockwise");
  expect_error(with("region", R"({"vertices": [[0,0],[1,0],[1,1]], "material": "granite"})"),
               "region.material", R"(unknown material "granite")");
  expect_error(
      [](json& d) {
        d["blocks"][1]["id"] = "region_1";
        d["region"] = json::parse(R"({"vertices": [[0,0],[1,0],[1,1]], "material": "rock"})");
      },
      "region.id_prefix", R"(the generated id "region_1" is also a block's)");
  expect_error(with("region", R"([{"vertices": [[0,0],[1,0],[1,1]], "material": "rock", "colour": 1}])"),
               "region[0].colour",
               "unknown field; expected only vertices, material, group, id_prefix, min_block_area");
  expect_error(with("region", R"({"vertices": [[0,0],[1,0],[1,1]], "material": "rock", "min_block_area": -1})"),
               "region.min_block_area", "a finite number >= 0");
  const auto with_set = [](const char* text) {
    return [text](json& d) {
      d["region"] = json::parse(R"({"vertices": [[0,0],[4,0],[4,4],[0,4]], "material": "rock"})");
      d["joint_sets"] = json::array({json::parse(text)});
    };
  };
  expect_error(with_set(R"({"dip_deg": 180, "spacing": 1})"), "joint_sets[0].dip_deg", "in [0, 180)");
  expect_error(with_set(R"({"dip_deg": 10, "spacing": 0})"), "joint_sets[0].spacing", "> 0");
  expect_error(with_set(R"({"dip_deg": 10, "spacing": 1, "gap": 1})"), "joint_sets[0].gap",
               R"(expected "length" beside it)");
  expect_error(with("interfaces", R"([{"between": ["a"]}])"), "interfaces[0].between",
               "the two groups [group, group]");
  expect_error(with("interfaces", R"([{"between": ["a", "b"], "mu": 1}])"), "interfaces[0].mu",
               "unknown field; expected only between, kn, kt, friction_angle_deg");
  expect_error(with("interfaces", R"([{"between": ["a", "b"]}, {"between": ["b", "a"]}])"),
               "interfaces[1].between", "already have an interface (interfaces[0])");
  expect_error(with("interfaces", R"([{"between": ["a", "b"], "friction_angle_deg": 90}])"),
               "interfaces[0].friction_angle_deg", "in [0, 90)");
  expect_error(with("interfaces", R"([{"between": ["a", "b"]}])"), "interfaces[0].between[0]",
               R"(no block, region or boundary is in the group "a")");
  expect_error(
      [](json& d) {
        d["contact"].erase("kt");
        d["contact"].erase("friction_angle_deg");
        d["interfaces"] = json::parse(R"([{"between": ["a", "b"], "friction_angle_deg": 20}])");
      },
      "interfaces[0].kt", "the scene's contact is frictionless");
}

// Stiffness warnings: the minimal scene (E = 2e8 Pa, kn = 5e7 Pa, frictionless) has none; kn
// below E / 1000 or above 100 E, and kt 1000 times off 2 kn, each get one naming the field.
BOOST_AUTO_TEST_CASE(stiffnesses_off_by_orders_of_magnitude_are_warned_about) {
  json document = minimal_scene();
  BOOST_TEST(dyn::stiffness_warnings(dyn::parse_scene(document, "minimal.json")).empty());
  const auto warnings = [&](double kn, double kt) {
    document["contact"]["kn"] = kn;
    document["contact"]["kt"] = kt;
    document["contact"]["friction_angle_deg"] = 30;
    return dyn::stiffness_warnings(dyn::parse_scene(document, "minimal.json"));
  };
  BOOST_TEST(warnings(5e7, 1e8).empty());  // kt = 2 kn
  auto w = warnings(1e5, 2e5);             // E / 2000
  BOOST_TEST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("contact.kn = 1e+05 Pa is below a thousandth") == 0u, w[0]);
  w = warnings(3e10, 6e10);  // 150 E
  BOOST_TEST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("contact.kn = 3e+10 Pa is above 100 times") == 0u, w[0]);
  w = warnings(5e7, 5e4);  // 2 kn / 2000
  BOOST_TEST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("contact.kt = 5e+04 N/m is more than 1000 times off") == 0u, w[0]);
}
