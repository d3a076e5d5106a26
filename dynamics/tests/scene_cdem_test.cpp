#define BOOST_TEST_MODULE scene_cdem
#include "rockcontact/dynamics/io/scene_cdem.hpp"

#include <array>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/testing/input_error.hpp"

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;
using nlohmann::json;

namespace {

// Every field of the format given once, none at its default: a fixed base, a block sliding onto
// it, a third block of another material.
json contract_scene() {
  return json::parse(R"({"format": "rockcontact-scene/1", "description": "contract",
   "dimension": 2, "solver": "cdem",
   "time": {"dt": 2e-6, "duration": 0.02},
   "gravity": [0.5, -9.8],
   "plane": "stress", "thickness": 0.25, "damping": 3.5,
   "materials": {"rock": {"density": 2700, "youngs_modulus": 4e10, "poisson_ratio": 0.25},
                 "soft": {"density": 1800, "youngs_modulus": 5e8, "poisson_ratio": -0.2}},
   "contact": {"law": "two-scale", "friction_angle_deg": 30, "cohesion": 1e5,
               "tensile_strength": 2e4, "search_tolerance": 5e-3, "subdivide": true,
               "policy": "exact"},
   "blocks": [{"id": "base", "material": "rock", "fixed": true,
               "vertices": [[0, -1], [4, -1], [4, 0], [0, 0]], "mesh": {"max_edge": 0.5}},
              {"id": "i", "material": "soft", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]],
               "velocity": [3.0, -0.5, 0.25], "mesh": {"max_edge": 0.05}},
              {"id": "j", "material": "rock", "vertices": [[2, 0], [3, 0], [2.5, 0.8]],
               "mesh": {"max_edge": 0.1}}],
   "output": {"track": ["j", "i"], "every": 10}})");
}

// The contract scene with only the required fields: the defaults below.
json minimal_scene() {
  return json::parse(R"({"solver": "cdem", "time": {"dt": 1e-5, "duration": 0.01},
   "materials": {"rock": {"density": 2700, "youngs_modulus": 4e10, "poisson_ratio": 0.25}},
   "contact": {"law": "two-scale", "search_tolerance": 1e-3},
   "blocks": [{"id": "base", "material": "rock", "fixed": true,
               "vertices": [[0, -1], [4, -1], [4, 0], [0, 0]], "mesh": {"max_edge": 0.5}},
              {"id": "i", "material": "rock", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]],
               "mesh": {"max_edge": 0.25}}]})");
}

// `change` applied to the contract scene must be rejected with an error naming the source, the
// JSON path and containing `expected`.
void expect_error(const std::function<void(json&)>& change, const std::string& path,
                  const std::string& expected) {
  json document = contract_scene();
  change(document);
  rockcontact::testing::expect_input_error(&dyn::parse_scene_cdem, document, path, expected);
}

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

}  // namespace

BOOST_AUTO_TEST_CASE(values_land_in_their_fields) {
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(contract_scene(), "contract.json");
  BOOST_TEST(scene.source == "contract.json");
  BOOST_TEST(scene.description == "contract");
  const dyn::CdemParams& p = scene.params;
  BOOST_TEST(p.dt == 2e-6);
  BOOST_TEST(scene.duration == 0.02);
  BOOST_TEST(p.gravity[0] == 0.5);
  BOOST_TEST(p.gravity[1] == -9.8);
  BOOST_TEST((p.plane == dyn::CdemPlane::stress));
  BOOST_TEST(p.thickness == 0.25);
  BOOST_TEST(p.damping == 3.5);
  const dyn::CdemContactParams& c = p.contact;
  BOOST_TEST((c.law == dyn::CdemLaw::two_scale));
  BOOST_TEST(c.friction_angle_deg == 30.0);
  BOOST_TEST(c.cohesion == 1e5);
  BOOST_TEST(c.tensile_strength == 2e4);
  BOOST_TEST(c.search_tolerance == 5e-3);
  BOOST_TEST(c.subdivide);
  BOOST_TEST((c.policy == kernel::PolicyKind::exact));
  BOOST_TEST_REQUIRE(scene.blocks.size() == 3u);
  const dyn::CdemBlockSpec& base = scene.blocks[0];
  BOOST_TEST(base.id == "base");
  BOOST_TEST(base.fixed);
  BOOST_TEST(base.max_edge == 0.5);
  BOOST_TEST(base.material.density == 2700.0);
  BOOST_TEST(base.material.youngs_modulus == 4e10);
  BOOST_TEST(base.material.poisson_ratio == 0.25);
  BOOST_TEST(base.velocity == (std::array<double, 3>{}));
  const dyn::CdemBlockSpec& i = scene.blocks[1];
  BOOST_TEST(!i.fixed);
  BOOST_TEST(i.max_edge == 0.05);
  BOOST_TEST(i.material.density == 1800.0);
  BOOST_TEST(i.material.youngs_modulus == 5e8);
  BOOST_TEST(i.material.poisson_ratio == -0.2);
  BOOST_TEST(i.velocity == (std::array<double, 3>{3.0, -0.5, 0.25}));
  BOOST_TEST_REQUIRE(i.vertices.size() == 4u);
  BOOST_TEST(i.vertices[2].x == 1.0);
  BOOST_TEST(i.vertices[2].y == 1.0);
  BOOST_TEST_REQUIRE(scene.blocks[2].vertices.size() == 3u);
  BOOST_TEST(scene.blocks[2].vertices[2].x == 2.5);
  BOOST_TEST(scene.blocks[2].vertices[2].y == 0.8);
  BOOST_TEST(scene.track == (std::vector<std::string>{"j", "i"}));  // the file's order
  BOOST_TEST(scene.every == 10u);
  BOOST_TEST(dyn::step_count(scene) == 10000u);
}

BOOST_AUTO_TEST_CASE(optional_fields_take_their_defaults) {
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(minimal_scene(), "minimal.json");
  BOOST_TEST(scene.description.empty());
  const dyn::CdemParams& p = scene.params;
  BOOST_TEST(p.gravity[0] == 0.0);
  BOOST_TEST(p.gravity[1] == -9.81);  // as in the 2D DDA scenes
  BOOST_TEST((p.plane == dyn::CdemPlane::strain));
  BOOST_TEST(p.thickness == 1.0);
  BOOST_TEST(p.damping == 0.0);
  const dyn::CdemContactParams& c = p.contact;
  BOOST_TEST(c.friction_angle_deg == 0.0);
  BOOST_TEST(c.cohesion == 0.0);
  BOOST_TEST(c.tensile_strength == 0.0);
  BOOST_TEST(!c.subdivide);
  BOOST_TEST((c.policy == kernel::PolicyKind::filtered));
  BOOST_TEST(c.kn == 0.0);  // not the two-scale law's
  BOOST_TEST(scene.blocks[0].fixed);
  BOOST_TEST(!scene.blocks[1].fixed);
  BOOST_TEST(scene.blocks[1].velocity == (std::array<double, 3>{}));
  BOOST_TEST(scene.every == 100u);
  BOOST_TEST(scene.track == std::vector<std::string>{"i"});  // the only block not fixed
  BOOST_TEST(dyn::step_count(scene) == 1000u);
}

// The penalty law: kn required, kt defaulting to kn; subdivide belongs to the two-scale law.
BOOST_AUTO_TEST_CASE(the_penalty_law_has_its_stiffnesses) {
  json document = minimal_scene();
  document["contact"] = {{"law", "penalty"}, {"kn", 2e9}, {"search_tolerance", 1e-3}};
  dyn::SceneCdem scene = dyn::parse_scene_cdem(document, "penalty.json");
  BOOST_TEST((scene.params.contact.law == dyn::CdemLaw::penalty));
  BOOST_TEST(scene.params.contact.kn == 2e9);
  BOOST_TEST(scene.params.contact.kt == 2e9);
  document["contact"]["kt"] = 5e8;
  scene = dyn::parse_scene_cdem(document, "penalty.json");
  BOOST_TEST(scene.params.contact.kt == 5e8);
  expect_error(
      [](json& d) {
        d["contact"] = {{"law", "penalty"}, {"kn", 1e9}, {"search_tolerance", 1e-3},
                        {"subdivide", true}};
      },
      "contact.subdivide", "belong to the two-scale law");
  expect_error(
      [](json& d) {
        d["contact"] = {{"law", "penalty"}, {"kn", 1e9}, {"kt", 0}, {"search_tolerance", 1e-3}};
      },
      "contact.kt", "expected the tangential penalty kt in N/m per node, a finite number > 0");
}

// The run covers the duration: duration / dt rounded up (1000.4 steps are 1001), but a quotient
// just off a whole number by the decimals' rounding (0.3 / 0.1 = 2.9999999999999996) is that
// number; and at least one step.
BOOST_AUTO_TEST_CASE(the_step_count_covers_the_duration) {
  json document = minimal_scene();
  document["time"] = {{"dt", 0.1}, {"duration", 0.3}};
  BOOST_TEST(dyn::step_count(dyn::parse_scene_cdem(document, "a.json")) == 3u);
  document["time"] = {{"dt", 1e-3}, {"duration", 1.0004}};
  BOOST_TEST(dyn::step_count(dyn::parse_scene_cdem(document, "b.json")) == 1001u);
  document["time"] = {{"dt", 1e-3}, {"duration", 2e-4}};
  BOOST_TEST(dyn::step_count(dyn::parse_scene_cdem(document, "c.json")) == 1u);
}

// Each malformed field is named by its JSON path, with what was expected.
BOOST_AUTO_TEST_CASE(bad_input_names_the_field) {
  expect_error([](json& d) { d["blocks"][0].erase("mesh"); }, "blocks[0].mesh",
               "missing field; expected the block's mesh size, an object {\"max_edge\": m > 0}");
  expect_error([](json& d) { d["blocks"][1]["mesh"]["max_edge"] = 0; }, "blocks[1].mesh.max_edge",
               "expected the longest element edge in m, a finite number > 0, got number 0");
  expect_error([](json& d) { d["blocks"][1]["mesh"]["size"] = 1; }, "blocks[1].mesh.size",
               "unknown field; expected only max_edge");
  expect_error([](json& d) { d["contact"]["tensile_strength"] = -1; }, "contact.tensile_strength",
               "expected the tensile strength in Pa, a finite number >= 0, got number -1");
  expect_error([](json& d) { d["contact"]["cohesion"] = -1; }, "contact.cohesion", ">= 0");
  expect_error([](json& d) { d["contact"]["law"] = "potential"; }, "contact.law",
               "expected one of \"two-scale\" (seed 003's clone nodes), \"penalty\" (node-to-edge "
               "springs), got string \"potential\"");
  expect_error([](json& d) { d["contact"]["kn"] = 1e9; }, "contact.kn",
               "belongs to the penalty law; expected no \"kn\" with \"law\": \"two-scale\"");
  expect_error([](json& d) { d["contact"]["kt"] = 1e9; }, "contact.kt",
               "belongs to the penalty law");
  expect_error(
      [](json& d) {
        d["contact"] = {{"law", "penalty"}, {"search_tolerance", 1e-3}};
      },
      "contact.kn", "missing field; expected the normal penalty kn in N/m per node");
  expect_error([](json& d) { d["contact"].erase("search_tolerance"); }, "contact.search_tolerance",
               "missing field");
  expect_error([](json& d) { d["contact"]["friction_angle_deg"] = 90; },
               "contact.friction_angle_deg", "a number in [0, 90)");
  expect_error([](json& d) { d["contact"]["policy"] = "fast"; }, "contact.policy",
               "one of \"float\", \"filtered\", \"exact\", \"checked\"");
  expect_error([](json& d) { d["colour"] = "red"; }, "colour",
               "unknown field; expected only format, description, dimension, solver");
  expect_error([](json& d) { d["blocks"][1]["rigid"] = true; }, "blocks[1].rigid",
               "unknown field");
  expect_error([](json& d) { d["blocks"][0]["velocity"] = {1, 0, 0}; }, "blocks[0].velocity",
               "a fixed block does not move; expected no velocity on it");
  expect_error([](json& d) { d["blocks"][1]["velocity"] = {1, 0}; }, "blocks[1].velocity",
               "expected the mass centre's velocity [vx, vy, omega]");
  expect_error([](json& d) { d["blocks"][1]["material"] = "granite"; }, "blocks[1].material",
               "unknown material \"granite\"; expected one of the scene's materials (rock, soft)");
  expect_error([](json& d) { d["blocks"][2]["id"] = "i"; }, "blocks[2].id",
               "duplicate id \"i\" (also blocks[1].id)");
  expect_error([](json& d) { d["blocks"][2]["id"] = ""; }, "blocks[2].id", "a non-empty string");
  expect_error([](json& d) { d["output"]["track"] = {"i", "ghost"}; }, "output.track[1]",
               "no block has the id \"ghost\"; expected a block id");
  expect_error([](json& d) { d["output"]["every"] = 0; }, "output.every", "an integer >= 1");
  expect_error([](json& d) { d["blocks"][2]["vertices"] = {{0, 0}, {1, 0}}; }, "blocks[2].vertices",
               "an array of at least 3 [x, y] vertices");
  expect_error([](json& d) { d["blocks"][2]["vertices"][1] = {1, "0"}; }, "blocks[2].vertices[1]",
               "expected a vertex, an [x, y] pair of numbers");
  expect_error([](json& d) { d["blocks"] = json::array(); }, "blocks",
               "a non-empty array of blocks");
  expect_error([](json& d) { d["materials"] = json::object(); }, "materials",
               "a non-empty object");
  expect_error([](json& d) { d["materials"]["rock"]["poisson_ratio"] = 0.5; },
               "materials.rock.poisson_ratio", "a number in (-1, 0.5)");
  expect_error([](json& d) { d["dimension"] = 3; }, "dimension", "expected 2");
  expect_error([](json& d) { d["plane"] = "axisymmetric"; }, "plane",
               "one of \"strain\", \"stress\"");
  expect_error([](json& d) { d["thickness"] = 0; }, "thickness", "a finite number > 0");
  expect_error([](json& d) { d["damping"] = -1; }, "damping", "a finite number >= 0");
  expect_error([](json& d) { d["time"]["duration"] = 0; }, "time.duration", "a finite number > 0");
  expect_error([](json& d) { d["time"]["dt"] = 1e-15; }, "time", "expected at most 1e12 steps");
  expect_error([](json& d) { d["format"] = "rockcontact-scene/2"; }, "format",
               "expected \"rockcontact-scene/1\"");
  expect_error([](json& d) { d.erase("contact"); }, "contact", "missing field");
}

// A document built in memory may hold NaN, which no file can: every number field refuses it.
BOOST_AUTO_TEST_CASE(non_finite_numbers_are_refused) {
  expect_error([](json& d) { d["time"]["dt"] = not_a_number; }, "time.dt",
               "got non-finite number");
  expect_error([](json& d) { d["gravity"][1] = not_a_number; }, "gravity[1]",
               "expected a finite number");
  expect_error([](json& d) { d["blocks"][1]["vertices"][2][0] = not_a_number; },
               "blocks[1].vertices[2]", "expected a vertex, an [x, y] pair of finite numbers");
  expect_error(
      [](json& d) { d["blocks"][1]["vertices"][0][1] = std::numeric_limits<double>::infinity(); },
      "blocks[1].vertices[0]", "finite numbers");
  expect_error([](json& d) { d["blocks"][1]["velocity"][2] = not_a_number; },
               "blocks[1].velocity[2]", "expected a finite number");
  expect_error([](json& d) { d["blocks"][1]["mesh"]["max_edge"] = not_a_number; },
               "blocks[1].mesh.max_edge", "got non-finite number");
  expect_error([](json& d) { d["contact"]["search_tolerance"] = not_a_number; },
               "contact.search_tolerance", "got non-finite number");
}

BOOST_AUTO_TEST_CASE(malformed_json_names_the_file) {
  rockcontact::testing::expect_malformed_json(
      [](const std::filesystem::path& file) { dyn::read_scene_cdem_file(file); },
      "rockcontact_scene_cdem_test_malformed.json",
      "{\"solver\": \"cdem\",\n \"time\": {\"dt\": 1e-3,}\n}\n");
}

// A CDEM scene says "solver": "cdem"; no other scene does, and the 3D test does not take it.
BOOST_AUTO_TEST_CASE(a_cdem_scene_is_told_by_its_solver) {
  BOOST_TEST(dyn::is_scene_cdem_document(contract_scene()));
  BOOST_TEST(dyn::is_scene_cdem_document(minimal_scene()));
  BOOST_TEST(!dyn::is_scene3d_document(contract_scene()));
  json other = contract_scene();
  other["solver"] = "dda";
  BOOST_TEST(!dyn::is_scene_cdem_document(other));
  other.erase("solver");
  BOOST_TEST(!dyn::is_scene_cdem_document(other));
  BOOST_TEST(!dyn::is_scene_cdem_document(json::array({"solver", "cdem"})));
  BOOST_TEST(!dyn::is_scene_cdem_document(json("cdem")));
}
