#define BOOST_TEST_MODULE scene3d
#include "rockcontact/dynamics/io/scene3d.hpp"

#include <algorithm>
#include <array>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/testing/box_json.hpp"
#include "rockcontact/testing/input_error.hpp"

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;
using nlohmann::json;

namespace {

const std::string scene_dir = ROCKCONTACT_DYNAMICS_TESTDATA_DIR "/scenes";
const std::string examples3d = ROCKCONTACT_EXAMPLES_DIR "/scenes3d";

using rockcontact::testing::box_json;

// A block {"id", "group", "material": "rock", "vertices", "faces"} of the box [lo, hi].
json box_block(const std::string& id, const std::string& group, std::array<double, 3> lo,
               std::array<double, 3> hi) {
  json b = box_json(lo, hi);
  b["id"] = id;
  b["group"] = group;
  b["material"] = "rock";
  return b;
}

// Every field of the format given once: a fixed slab, a cube on it, a fixed two-part wall.
json contract_scene() {
  json scene = json::parse(R"({"dimension": 3,
   "time": {"dt": 2e-4, "duration": 0.5, "max_displacement_ratio": 0.002, "max_rotation_deg": 2.5},
   "gravity": [0.5, 0, -9.81],
   "materials": {"rock": {"density": 2600, "youngs_modulus": 1e10, "poisson_ratio": 0.25},
                 "soft": {"density": 1800, "youngs_modulus": 5e8, "poisson_ratio": 0.3}},
   "contact": {"law": "penalty", "kn": 2e10, "kt": 3e9, "friction_angle_deg": 35, "cohesion": 100,
               "tensile_strength": 50, "policy": "exact"},
   "interfaces": [{"between": ["ground", "rock"], "friction_angle_deg": 20, "cohesion": 7}],
   "output": {"track": ["cube"], "every": 10}})");
  json slab = box_block("slab", "ground", {-2, -2, -1}, {2, 2, 0});
  slab["fixed"] = true;
  json cube = box_block("cube", "rock", {-0.5, -0.5, 0}, {0.5, 0.5, 1});
  cube["material"] = "soft";
  cube["rigid"] = true;
  cube["velocity"] = {1, 2, 3, 0.1, 0.2, 0.3};
  json wall = {{"id", "wall"},
               {"group", "ground"},
               {"material", "rock"},
               {"fixed", true},
               {"parts", {box_json({2, -2, 0}, {3, 2, 1}), box_json({2, 2, 0}, {3, 3, 1})}}};
  scene["blocks"] = {slab, cube, wall};
  return scene;
}

// `change` applied to the contract scene must be rejected with an error naming the source, the
// JSON path and containing `expected`.
void expect_error(const std::function<void(json&)>& change, const std::string& path,
                  const std::string& expected) {
  json document = contract_scene();
  change(document);
  rockcontact::testing::expect_input_error(&dyn::parse_scene3d, document, path, expected);
}

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

}  // namespace

BOOST_AUTO_TEST_CASE(values_land_in_their_fields) {
  const dyn::Scene3d scene = dyn::parse_scene3d(contract_scene(), "contract.json");
  BOOST_TEST(scene.source == "contract.json");
  BOOST_TEST(scene.params.dt == 2e-4);
  BOOST_TEST(scene.duration == 0.5);
  BOOST_TEST(scene.params.max_displacement_ratio == 0.002);
  BOOST_TEST(scene.params.max_rotation_deg == 2.5);
  BOOST_TEST(scene.params.gravity[0] == 0.5);
  BOOST_TEST(scene.params.gravity[1] == 0.0);
  BOOST_TEST(scene.params.gravity[2] == -9.81);
  BOOST_TEST(scene.law.kn == 2e10);
  BOOST_TEST(scene.law.kt == 3e9);
  BOOST_TEST(scene.law.friction_angle_deg == 35.0);
  BOOST_TEST(scene.law.cohesion == 100.0);
  BOOST_TEST(scene.law.tensile_strength == 50.0);
  BOOST_TEST((scene.law.policy == kernel::PolicyKind::exact));
  BOOST_TEST_REQUIRE(scene.law.interfaces.size() == 1u);
  const dyn::Interface3d& face = scene.law.interfaces[0];
  BOOST_TEST(face.groups[0] == "ground");
  BOOST_TEST(face.groups[1] == "rock");
  BOOST_TEST(face.friction_angle_deg == 20.0);
  BOOST_TEST(face.cohesion == 7.0);
  BOOST_TEST(face.tensile_strength == 50.0);  // left out: the contact's
  BOOST_TEST_REQUIRE(scene.blocks.size() == 3u);
  const dyn::Block3dSpec& slab = scene.blocks[0];
  BOOST_TEST(slab.id == "slab");
  BOOST_TEST(slab.group == "ground");
  BOOST_TEST(slab.fixed);
  BOOST_TEST(!slab.rigid);
  BOOST_TEST(slab.material.density == 2600.0);
  BOOST_TEST_REQUIRE(slab.parts.size() == 1u);
  BOOST_TEST(slab.parts[0].size() == 8u);
  BOOST_TEST(slab.parts[0].input_faces().size() == 6u);
  BOOST_TEST(slab.parts[0][6].x == 2.0);
  BOOST_TEST(slab.parts[0][6].z == 0.0);
  const dyn::Block3dSpec& cube = scene.blocks[1];
  BOOST_TEST(!cube.fixed);
  BOOST_TEST(cube.rigid);
  BOOST_TEST(cube.material.density == 1800.0);
  BOOST_TEST(cube.material.youngs_modulus == 5e8);
  BOOST_TEST(cube.material.poisson_ratio == 0.3);
  const std::array<double, 6> velocity{1, 2, 3, 0.1, 0.2, 0.3};
  BOOST_TEST(cube.velocity == velocity);
  BOOST_TEST(scene.blocks[2].parts.size() == 2u);
  BOOST_TEST(scene.blocks[2].fixed);
  BOOST_TEST(scene.material_names[1] == "soft");
  BOOST_TEST(scene.generated_count == 0u);
  BOOST_TEST(scene.track == std::vector<std::string>{"cube"});
  BOOST_TEST(scene.every == 10u);
}

BOOST_AUTO_TEST_CASE(optional_fields_take_their_defaults) {
  json document = contract_scene();
  for (const char* key : {"gravity", "interfaces", "output"}) document.erase(key);
  document["time"].erase("max_displacement_ratio");
  document["time"].erase("max_rotation_deg");
  for (const char* key : {"friction_angle_deg", "cohesion", "tensile_strength", "policy"}) {
    document["contact"].erase(key);
  }
  document["blocks"][1].erase("velocity");
  document["blocks"][1].erase("rigid");
  const dyn::Scene3d scene = dyn::parse_scene3d(document, "defaults.json");
  BOOST_TEST(scene.params.max_displacement_ratio == 0.001);
  BOOST_TEST(scene.params.max_rotation_deg == 1.0);
  BOOST_TEST(scene.params.gravity[2] == -9.81);
  BOOST_TEST(scene.law.friction_angle_deg == 0.0);
  BOOST_TEST(scene.law.cohesion == 0.0);
  BOOST_TEST(scene.law.tensile_strength == 0.0);
  BOOST_TEST((scene.law.policy == kernel::PolicyKind::filtered));
  BOOST_TEST(scene.law.interfaces.empty());
  BOOST_TEST(!scene.blocks[1].rigid);
  BOOST_TEST(scene.blocks[1].velocity == (std::array<double, 6>{}));
  BOOST_TEST(scene.every == 100u);
  BOOST_TEST(scene.track == std::vector<std::string>{"cube"});  // the only block not fixed
  BOOST_TEST((scene.params.initial_equilibrium == dyn::InitialEquilibrium::automatic));
  BOOST_TEST(!scene.params.static_analysis);
}

BOOST_AUTO_TEST_CASE(analysis_and_initial_equilibrium) {
  json document = contract_scene();
  document["analysis"] = "static";
  document["initial_equilibrium"] = false;
  const dyn::Scene3d scene = dyn::parse_scene3d(document, "static.json");
  BOOST_TEST(scene.params.static_analysis);
  BOOST_TEST((scene.params.initial_equilibrium == dyn::InitialEquilibrium::off));
  document["initial_equilibrium"] = "auto";
  BOOST_TEST((dyn::parse_scene3d(document, "auto.json").params.initial_equilibrium ==
              dyn::InitialEquilibrium::automatic));
  document["initial_equilibrium"] = true;
  BOOST_TEST((dyn::parse_scene3d(document, "strict.json").params.initial_equilibrium ==
              dyn::InitialEquilibrium::strict));
  document["analysis"] = "dynamic";
  BOOST_TEST(!dyn::parse_scene3d(document, "dynamic.json").params.static_analysis);
  expect_error([](json& d) { d["analysis"] = "quasi"; }, "analysis", "one of \"dynamic\", \"static\"");
  expect_error([](json& d) { d["contact"]["damping_ratio"] = -0.5; }, "contact.damping_ratio",
               "critical damping ratio, a finite number >= 0");
  document["contact"]["damping_ratio"] = 0.5;
  BOOST_TEST(dyn::parse_scene3d(document, "damped.json").law.damping_ratio == 0.5);
  expect_error([](json& d) { d["initial_equilibrium"] = 1; }, "initial_equilibrium", R"("auto", true or false)");
}

// Each malformed field is named by its JSON path, with what was expected.
BOOST_AUTO_TEST_CASE(bad_input_names_the_field) {
  expect_error([](json& d) { d["colour"] = "red"; }, "colour",
               "unknown field; expected only format");
  expect_error([](json& d) { d["blocks"][1]["mass"] = 1; }, "blocks[1].mass", "unknown field");
  expect_error([](json& d) { d["dimension"] = 2; }, "dimension", "expected 3, got number 2");
  expect_error([](json& d) { d["time"]["dt"] = not_a_number; }, "time.dt",
               "expected the largest time step");
  expect_error([](json& d) { d["gravity"][2] = not_a_number; }, "gravity[2]",
               "expected a finite number");
  for (const double ratio : {0.0, 1.0, -0.5, 1.5}) {
    expect_error([&](json& d) { d["time"]["max_displacement_ratio"] = ratio; },
                 "time.max_displacement_ratio",
                 "expected the largest vertex displacement of a step over the scene's size, a "
                 "number in (0, 1)");
  }
  expect_error([](json& d) { d["time"]["max_displacement_ratio"] = not_a_number; },
               "time.max_displacement_ratio", "a number in (0, 1), got non-finite number");
  for (const double angle : {0.0, 90.0, -1.0}) {
    expect_error([&](json& d) { d["time"]["max_rotation_deg"] = angle; }, "time.max_rotation_deg",
                 "expected the largest rotation of a block in a step, degrees, a number in (0, 90)");
  }
  expect_error([](json& d) { d["blocks"][1]["material"] = "granite"; }, "blocks[1].material",
               "unknown material \"granite\"; expected one of the scene's materials (rock, soft)");
  expect_error([](json& d) { d["blocks"][2]["id"] = "slab"; }, "blocks[2].id",
               "duplicate id \"slab\" (also blocks[0].id)");
  expect_error([](json& d) { d["interfaces"][0]["between"][1] = "rocks"; },
               "interfaces[0].between[1]", "no block is in the group \"rocks\"");
  expect_error(
      [](json& d) {
        d["interfaces"].push_back({{"between", {"rock", "ground"}}});
      },
      "interfaces[1].between", "already have an interface (interfaces[0])");
  expect_error([](json& d) { d["interfaces"][0]["friction_angle_deg"] = 90; },
               "interfaces[0].friction_angle_deg", "a number in [0, 90)");
  expect_error([](json& d) { d["contact"]["law"] = "potential"; }, "contact.law",
               "expected \"penalty\"");
  expect_error([](json& d) { d["contact"]["kn"] = "stiff"; }, "contact.kn",
               "a finite number > 0, or \"auto\"");
  expect_error([](json& d) { d["contact"]["kt"] = -1; }, "contact.kt", "a finite number > 0, or \"auto\"");
  expect_error([](json& d) { d["contact"]["tensile_strength"] = -1; }, "contact.tensile_strength",
               "a finite number >= 0");
  expect_error([](json& d) { d["blocks"][0]["velocity"] = {0, 0, 0, 0, 0, 0}; },
               "blocks[0].velocity", "a fixed block does not move");
  expect_error(
      [](json& d) {
        d["blocks"][1]["velocity"] = {0, 0, 0, 0, 0};
      },
      "blocks[1].velocity", "expected the centroid velocity [vx, vy, vz, wx, wy, wz]");
  expect_error(
      [](json& d) {
        d["blocks"][1]["parts"] = json::array({box_json({0, 0, 0}, {1, 1, 1})});
      },
      "blocks[1]", "expected exactly one of \"vertices\" with \"faces\"");
  expect_error([](json& d) { d["blocks"][1].erase("faces"); }, "blocks[1].faces", "missing field");
  expect_error([](json& d) { d["blocks"][1]["faces"][2][1] = -1; }, "blocks[1].faces[2][1]",
               "expected a vertex index, an integer >= 0");
  expect_error(
      [](json& d) {
        d["output"]["track"] = {"slab", "ghost"};
      },
      "output.track[1]", "no block has the id \"ghost\"");
  expect_error([](json& d) { d["output"]["every"] = 0; }, "output.every", "an integer >= 1");
  expect_error([](json& d) { d["joint_sets"] = json::array(); }, "joint_sets",
               "expected a \"region\" beside them");
  expect_error([](json& d) { d.erase("blocks"); }, "blocks", "the scene has no blocks");
}

// The kernel's InvalidPolyhedron mapped onto the JSON path of the face or vertex it names.
// "kn": "auto" (or none) is 10 E L of the movable block with the smallest E L, L the cube root of
// its volume (dda3d.hpp); "kt": "auto" (or none) is kn / 10. The contract scene's one movable
// block is the 1 m cube of "soft" (E = 5e8 Pa): kn = 10 x 5e8 x 1 = 5e9 N/m. Made of "rock"
// (1e10 Pa) beside a movable 2 m "soft" cube (E L = 1e9), the smaller E L is the second's.
// Fixed blocks do not count (the slab's E L is 2.5e10). The volume is a sum of exact
// tetrahedra of a box (relative error of a few ulps), hence the 1e-12.
BOOST_AUTO_TEST_CASE(penalties_default_to_auto) {
  const auto parse = [](const std::function<void(json&)>& change) {
    json document = contract_scene();
    change(document);
    return dyn::parse_scene3d(document, "auto.json");
  };
  const auto tolerance = boost::test_tools::tolerance(1e-12);
  const dyn::Scene3d none = parse([](json& d) { d["contact"].erase("kn"), d["contact"].erase("kt"); });
  BOOST_TEST(none.law.kn == 5.0e9, tolerance);
  BOOST_TEST(none.law.kt == 5.0e8, tolerance);
  BOOST_TEST((none.kn_auto && none.kt_auto));
  const dyn::Scene3d asked = parse([](json& d) { d["contact"]["kn"] = "auto"; });
  BOOST_TEST(asked.law.kn == 5.0e9, tolerance);
  BOOST_TEST(asked.law.kt == 3.0e9);
  BOOST_TEST((asked.kn_auto && !asked.kt_auto));
  const dyn::Scene3d given = parse([](json& d) { d["contact"].erase("kt"); });
  BOOST_TEST(given.law.kn == 2.0e10);
  BOOST_TEST(given.law.kt == 2.0e9, tolerance);
  const dyn::Scene3d two = parse([](json& d) {
    d["contact"]["kn"] = "auto";
    d["blocks"][1]["material"] = "rock";
    json big = box_block("big", "rock", {5, 5, 0}, {7, 7, 2});
    big["material"] = "soft";
    d["blocks"].push_back(big);
  });
  BOOST_TEST(two.law.kn == 10.0 * 5.0e8 * 2.0, tolerance);
}

BOOST_AUTO_TEST_CASE(invalid_polyhedra_name_the_face_or_vertex) {
  // The top face left out: the top edge 4 -> 7 of the side face now at index 4 has no reverse.
  expect_error([](json& d) { d["blocks"][1]["faces"].erase(1); }, "blocks[1].faces[4]",
               "polyhedron 'cube', face 4, vertex 4: edge 4 -> 7 has no neighbouring face "
               "traversing it back");
  // The top face clockwise seen from outside: its edge 5 -> 4 runs as face 2's does.
  expect_error(
      [](json& d) {
        d["blocks"][1]["faces"][1] = {7, 6, 5, 4};
      },
      "blocks[1].faces[2]",
      "polyhedron 'cube', face 2, vertex 5: edge 5 -> 4 is traversed in the same direction by face "
      "1");
  expect_error([](json& d) { d["blocks"][1]["vertices"][6][2] = not_a_number; },
               "blocks[1].vertices[6]", "polyhedron 'cube', vertex 6");
  expect_error([](json& d) { d["blocks"][2]["parts"][1]["vertices"][0][0] = not_a_number; },
               "blocks[2].parts[1].vertices[0]", "polyhedron 'wall.2', vertex 0");
  // Zero volume: a "tetrahedron" whose four vertices lie in the plane z = 0.
  expect_error(
      [](json& d) {
        d["blocks"][1]["vertices"] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 0}};
        d["blocks"][1]["faces"] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
      },
      "blocks[1].vertices", "polyhedron 'cube': every vertex lies in one plane, zero volume");
}

BOOST_AUTO_TEST_CASE(malformed_json_names_the_file) {
  rockcontact::testing::expect_malformed_json(
      [](const std::filesystem::path& file) { dyn::read_scene3d_file(file); },
      "rockcontact_scene3d_test_malformed.json",
      "{\"dimension\": 3,\n \"time\": {\"dt\": 1e-3,}\n}\n");
}

// The 2D reader says where a 3D scene goes; the 3D reader reads it.
BOOST_AUTO_TEST_CASE(the_readers_dispatch_on_the_dimension) {
  const json document = contract_scene();
  BOOST_TEST(dyn::is_scene3d_document(document));
  try {
    dyn::parse_scene(document, "case.json");
    BOOST_ERROR("the 2D reader accepted a 3D scene");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "dimension");
    BOOST_TEST(std::string(e.what()).find("a 3D scene, read by parse_scene3d") !=
               std::string::npos);
  }
  BOOST_TEST(dyn::read_scene3d_file(scene_dir + "/three_d.json").blocks.size() == 2u);
}

// The shipped 3D scenes (examples/scenes3d/README.md): the §6.1 wedge on its fixed, non-convex
// base, and the 18 blocks of §6.3 on a ground slab.
BOOST_AUTO_TEST_CASE(the_example_scenes_parse) {
  const dyn::Scene3d wedge = dyn::read_scene3d_file(examples3d + "/wedge.json");
  BOOST_TEST_REQUIRE(wedge.blocks.size() == 2u);
  BOOST_TEST(wedge.blocks[0].id == "base");
  BOOST_TEST(wedge.blocks[0].fixed);
  BOOST_TEST(wedge.blocks[0].parts.size() == 3u);
  BOOST_TEST(wedge.blocks[1].id == "wedge");
  BOOST_TEST(wedge.law.interfaces.size() == 1u);
  BOOST_TEST(wedge.track == std::vector<std::string>{"wedge"});
  BOOST_TEST(wedge.every == 10u);
  const dyn::Scene3d system = dyn::read_scene3d_file(examples3d + "/block_system.json");
  BOOST_TEST(system.blocks.size() == 19u);
  BOOST_TEST(system.track.size() == 18u);
  BOOST_TEST(system.law.friction_angle_deg == 0.0);
}

// "region" + "joint_sets" as `rockcontact cut` reads them: a 2 m tall box cut by horizontal
// joints at z = 0.5 and 1.5 is three slabs, "r_1" .. "r_3", after the explicit blocks.
BOOST_AUTO_TEST_CASE(a_region_is_cut_into_blocks) {
  json document = contract_scene();
  document["region"] = {{"box", {{"min", {-1, -1, 0}}, {"max", {1, 1, 2}}}},
                        {"material", "soft"},
                        {"group", "rock"},
                        {"id_prefix", "r"}};
  document["joint_sets"] = {
      {{"dip_deg", 0}, {"dip_direction_deg", 0}, {"spacing", 1}, {"offset", 0.5}}};
  document["blocks"].erase(1);
  document.erase("output");
  const dyn::Scene3d scene = dyn::parse_scene3d(document, "region.json");
  BOOST_TEST(scene.generated_first == 2u);
  BOOST_TEST_REQUIRE(scene.generated_count == 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const dyn::Block3dSpec& b = scene.blocks[2 + k];
    BOOST_TEST(b.id == "r_" + std::to_string(k + 1));
    BOOST_TEST(b.group == "rock");
    BOOST_TEST(b.material.density == 1800.0);
    BOOST_TEST(!b.fixed);
    BOOST_TEST(scene.material_names[2 + k] == "soft");
  }
  BOOST_TEST(scene.track == (std::vector<std::string>{"r_1", "r_2", "r_3"}));

  document["joint_sets"][0]["spacing"] = -1;
  try {
    dyn::parse_scene3d(document, "region.json");
    BOOST_ERROR("accepted a negative spacing");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "joint_sets[0].spacing");
  }
  document["joint_sets"][0]["spacing"] = 1;
  document["region"].erase("material");
  try {
    dyn::parse_scene3d(document, "region.json");
    BOOST_ERROR("accepted a region without a material");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "region.material");
  }
  document["region"]["material"] = "soft";
  document["region"]["id_prefix"] = "slab";
  document["region"]["box"]["max"][2] = 0.4;  // below the first joint: one block, "slab_1"
  document["blocks"][0]["id"] = "slab_1";
  try {
    dyn::parse_scene3d(document, "region.json");
    BOOST_ERROR("accepted a generated id equal to a block's");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "region.id_prefix");
  }
}

namespace {

// The scene of a_region_is_cut_into_blocks: the box [-1, 1]² x [0, 2] in place of the cube, cut
// by the joints z = 0.5 and 1.5 into slabs of 2, 4 and 2 m³.
json region_scene() {
  json document = contract_scene();
  document["region"] = {{"box", {{"min", {-1, -1, 0}}, {"max", {1, 1, 2}}}},
                        {"material", "soft"},
                        {"group", "rock"},
                        {"id_prefix", "r"}};
  document["joint_sets"] = {{{"dip_deg", 0}, {"dip_direction_deg", 0}, {"spacing", 1}, {"offset", 0.5}}};
  document["blocks"].erase(1);
  document.erase("output");
  return document;
}

double block_volume(const dyn::Block3dSpec& block) {
  double volume = 0;
  for (const auto& part : block.parts) volume += kernel::moments(part).volume;
  return volume;
}

}  // namespace

// region.min_block_volume: the slabs of region_scene.
//   - Default ("auto"): 1e-3 of the region's 8 m³ per block of the cut's 3, 8/3e-3 m³: nothing
//     merges.
//   - 2.5 m³: both end slabs (2 m³) are below; the lower one goes first (equal volumes, lower
//     index) into its only neighbour, the middle slab (6 m³ then), and the upper one follows
//     into it: one block, "r_1", of 8 m³ in three parts, the middle slab's first.
// Volumes of boxes are exact in double up to the tetrahedra's division by 6: 1e-14.
BOOST_AUTO_TEST_CASE(a_region_merges_blocks_below_min_block_volume) {
  const auto tolerance = boost::test_tools::tolerance(1e-14);
  json document = region_scene();
  const dyn::Scene3d automatic = dyn::parse_scene3d(document, "region.json");
  BOOST_TEST(automatic.generated_count == 3u);
  BOOST_TEST(automatic.merged_fragments == 0u);
  BOOST_TEST(automatic.min_block_volume == 8e-3 / 3, tolerance);
  document["region"]["min_block_volume"] = 2.5;
  const dyn::Scene3d merged = dyn::parse_scene3d(document, "region.json");
  BOOST_TEST_REQUIRE(merged.generated_count == 1u);
  BOOST_TEST(merged.merged_fragments == 2u);
  BOOST_TEST(merged.min_block_volume == 2.5);
  const dyn::Block3dSpec& block = merged.blocks[merged.generated_first];
  BOOST_TEST(block.id == "r_1");
  BOOST_TEST_REQUIRE(block.parts.size() == 3u);
  BOOST_TEST(kernel::moments(block.parts[0]).volume == 4.0, tolerance);
  BOOST_TEST(block_volume(block) == 8.0, tolerance);
  BOOST_TEST(merged.track == std::vector<std::string>{"r_1"});

  expect_error([](json& d) { d = region_scene(); d["region"]["min_block_volume"] = -1; }, "region.min_block_volume",
               "expected the volume in m³ below which a cut block is merged into a neighbour, a finite number >= 0, "
               "or \"auto\"");
  expect_error([](json& d) { d = region_scene(); d["region"]["min_block_volume"] = "bogus"; },
               "region.min_block_volume",
               "or \"auto\" (the default: 1e-3 of the region's volume per block of the cut), got string \"bogus\"");
  expect_error([](json& d) { d = region_scene(); d["region"]["colour"] = "grey"; }, "region.colour",
               "unknown field; expected only vertices, faces, box, parts, material, group, id_prefix, "
               "min_block_volume");
}

// The jointed mass (examples/scenes3d/jointed_mass.json) under the default "auto": cut with
// min_block_volume 0, its box of 144 m³ makes 147 blocks, so auto is 1e-3 x 144 / 147 =
// 9.8e-4 m³, and exactly two blocks are below it, the slivers of 3.3e-5 and 9.8e-5 m³. The next
// one, 9.9e-4 m³, is above it by 1.1 %: far more than the volumes' rounding (a few ulps), so no
// rounding decides which blocks are fragments, but a bound 1.2 % larger would take it too; the
// ones after are 1.5e-3 m³ and more. A block of a box cut by
// planes always shares a face with another, and a merge leaves one block fewer whichever block
// receives it (a sliver merged into the other sliver is still below the bound and merges
// again), so the default cut has 147 - 2 = 145 blocks, every one of them at least the bound,
// their volumes still summing to 144 m³ (1e-12, as in examples3d_test). "auto" given is the
// default.
BOOST_AUTO_TEST_CASE(the_jointed_mass_merges_its_two_slivers_by_default) {
  const std::string file = examples3d + "/jointed_mass.json";
  json document = dyn::read_json_file(file);
  document["region"]["min_block_volume"] = 0;
  const dyn::Scene3d unmerged = dyn::parse_scene3d(document, file);
  BOOST_TEST_REQUIRE(unmerged.generated_count == 147u);
  BOOST_TEST(unmerged.merged_fragments == 0u);
  std::vector<double> volumes;
  for (std::size_t i = unmerged.generated_first; i < unmerged.blocks.size(); ++i) {
    volumes.push_back(block_volume(unmerged.blocks[i]));
  }
  std::sort(volumes.begin(), volumes.end());
  const double bound = 1e-3 * 144.0 / 147.0;
  const auto below =
      static_cast<std::size_t>(std::count_if(volumes.begin(), volumes.end(), [&](double v) { return v < bound; }));
  BOOST_TEST(below == 2u);
  BOOST_TEST(volumes[0] == 3.3e-5, boost::test_tools::tolerance(0.02));
  BOOST_TEST(volumes[1] == 9.8e-5, boost::test_tools::tolerance(0.02));
  BOOST_TEST(volumes[2] == 9.9e-4, boost::test_tools::tolerance(0.01));
  BOOST_TEST(volumes[2] > 1.01 * bound);

  const dyn::Scene3d merged = dyn::read_scene3d_file(file);
  BOOST_TEST(merged.min_block_volume == bound, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(merged.merged_fragments == below);
  BOOST_TEST(merged.generated_count == 147u - below);
  double sum = 0;
  for (std::size_t i = merged.generated_first; i < merged.blocks.size(); ++i) {
    const double volume = block_volume(merged.blocks[i]);
    BOOST_TEST(volume >= bound);
    sum += volume;
  }
  BOOST_TEST(sum == 144.0, boost::test_tools::tolerance(1e-12));
  document["region"]["min_block_volume"] = "auto";
  BOOST_TEST(dyn::parse_scene3d(document, file).generated_count == 145u);
}
