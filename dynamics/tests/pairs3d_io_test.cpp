#define BOOST_TEST_MODULE pairs3d_io
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/apps/pairs_summary.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/testing/json_file.hpp"

// The `pairs` contract in 3D (pairs_io.hpp): closed forms for a cube resting on and pressed into
// another, the independent contact3d reference through the JSON layer, and bad input named by
// its path.

namespace dyn = rockcontact::dynamics;
using nlohmann::json;
using nlohmann::ordered_json;

namespace {

json box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{"vertices", {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                        {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}},
          {"faces", {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}};
}

// The user guide's example: a 0.5 m cube on a unit cube, its base at height `z`.
json cube_on_cube(double z, double tolerance = 0.0) {
  json document = {{"dimension", 3}, {"kn", 1e9},
                   {"pairs", {{{"id", "cube on cube"}, {"cp", box(0, 0, 0, 1, 1, 1)},
                               {"tp", box(0.25, 0.25, z, 0.75, 0.75, z + 0.5)}}}}};
  if (tolerance > 0) document["tolerance"] = tolerance;
  return document;
}

ordered_json run(const json& document, const dyn::PairsOverrides& overrides = {}) {
  return dyn::run_pairs(dyn::parse_pairs(document, "case.json"), overrides);
}

void expect_input_error(const json& document, const std::string& path, const std::string& words,
                        const dyn::PairsOverrides& overrides = {}) {
  BOOST_TEST_CONTEXT("path " << path) {
    try {
      run(document, overrides);
      BOOST_ERROR("accepted a malformed document");
    } catch (const dyn::InputError& e) {
      BOOST_TEST(e.path() == path);
      BOOST_TEST_INFO(e.what());
      BOOST_TEST(std::string(e.what()).find(words) != std::string::npos);
    }
  }
}

// The four vertex-face constraints of the cube's base corners on the top face z = 1.
void expect_base_corners(const ordered_json& constraints, double gap, double force) {
  BOOST_TEST(constraints.size() == 4u);
  for (const auto& c : constraints) {
    BOOST_TEST(c.at("type") == "vertex-face");
    BOOST_TEST((c.at("normal") == json::array({0.0, 0.0, 1.0})));
    BOOST_TEST(c.at("gap").get<double>() == gap, boost::test_tools::tolerance(1e-12));
    const auto& p = c.at("point_tp");
    BOOST_TEST((p[0] == 0.25 || p[0] == 0.75));
    BOOST_TEST((p[1] == 0.25 || p[1] == 0.75));
    BOOST_TEST(c.at("point_cp")[2].get<double>() == 1.0);
    BOOST_TEST(c.at("force")[2].get<double>() == force, boost::test_tools::tolerance(1e-9));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_cube_resting_on_a_cube) {
  const ordered_json out = run(cube_on_cube(1.0));
  BOOST_TEST(out.at("policy") == "filtered");
  const auto& r = out.at("results").at(0);
  BOOST_TEST(r.at("status") == "touch");
  BOOST_TEST(r.at("volume").get<double>() == 0.0);
  BOOST_TEST(r.at("distance").is_null());
  BOOST_TEST(r.at("penetration").is_null());
  // The contact set is the square [0.25, 0.75]² at z = 1: four corners, dimension 2.
  BOOST_TEST(r.at("contact_set").at("dimension") == 2);
  const auto& corners = r.at("contact_set").at("vertices");
  BOOST_TEST(corners.size() == 4u);
  for (const auto& p : corners) {
    BOOST_TEST((p[0] == 0.25 || p[0] == 0.75));
    BOOST_TEST((p[1] == 0.25 || p[1] == 0.75));
    BOOST_TEST(p[2] == 1.0);
  }
  expect_base_corners(r.at("constraints"), 0.0, 0.0);
}

BOOST_AUTO_TEST_CASE(a_cube_pressed_into_a_cube) {
  // Base 1e-3 below the top: the intersection is 0.5 x 0.5 x 1e-3 m³, the minimum translation
  // 1e-3 m straight up, and each corner's penalty force kn * 1e-3 = 1e6 N up on tp. (The
  // coordinates 1 - 1e-3 and its sum with 0.5 are rounded; 1e-12 relative covers it.)
  const ordered_json out = run(cube_on_cube(1.0 - 1e-3));
  const auto& r = out.at("results").at(0);
  BOOST_TEST(r.at("status") == "overlap");
  BOOST_TEST(r.at("volume").get<double>() == 2.5e-4, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.at("penetration").at("depth").get<double>() == 1e-3, boost::test_tools::tolerance(1e-12));
  BOOST_TEST((r.at("penetration").at("normal") == json::array({0.0, 0.0, 1.0})));
  BOOST_TEST(r.at("contact_set").is_null());
  expect_base_corners(r.at("constraints"), -1e-3, 1e6);
}

BOOST_AUTO_TEST_CASE(tolerance_lists_constraints_of_near_pairs) {
  // 0.1 m apart: separate at distance 0.1; constraints only with a tolerance above it, with a
  // positive gap and no force.
  const ordered_json apart_out = run(cube_on_cube(1.1));
  const auto& apart = apart_out.at("results").at(0);
  BOOST_TEST(apart.at("status") == "separate");
  BOOST_TEST(apart.at("distance").get<double>() == 0.1, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(apart.at("constraints").empty());
  const ordered_json near_out = run(cube_on_cube(1.1, 0.2));
  const auto& near = near_out.at("results").at(0);
  expect_base_corners(near.at("constraints"), 0.1, 0.0);
}

BOOST_AUTO_TEST_CASE(contact3d_reference_through_the_json_layer) {
  // The independent reference (robustness_tests/data/contact3d) with its README's tolerances:
  // statuses exact; volume, distance and depth within 1e-9 relative or 1e-12 scale (scale³ for
  // volumes); contact-set dimension exact.
  const std::string dir = std::string(ROCKCONTACT_TESTDATA_DIR) + "/contact3d";
  const json input = rockcontact::testing::read_json(dir + "/pairs.json");
  const json expected = rockcontact::testing::read_json(dir + "/expected.json");
  for (const char* policy : {"filtered", "exact"}) {
    dyn::PairsOverrides overrides;
    overrides.policy = rockcontact::kernel::parse_policy(policy);
    const ordered_json out = run(input, overrides);
    const auto& results = out.at("results");
    BOOST_TEST_REQUIRE(results.size() == expected.at("results").size());
    for (std::size_t i = 0; i < results.size(); ++i) {
      const auto& r = results[i];
      const auto& x = expected.at("results")[i];
      BOOST_TEST_CONTEXT(policy << " " << x.at("id")) {
        const double scale = std::stod(x.at("scale").get<std::string>());
        BOOST_TEST(r.at("status") == x.at("status"));
        const double volume = std::stod(x.at("volume").get<std::string>());
        BOOST_TEST(std::abs(r.at("volume").get<double>() - volume) <= 1e-9 * volume + 1e-12 * std::pow(scale, 3));
        if (!x.at("distance").is_null()) {
          const double d = std::stod(x.at("distance").get<std::string>());
          BOOST_TEST(std::abs(r.at("distance").get<double>() - d) <= 1e-9 * d + 1e-12 * scale);
        }
        if (!x.at("penetration").is_null()) {
          const double d = std::stod(x.at("penetration").at("depth").get<std::string>());
          BOOST_TEST(std::abs(r.at("penetration").at("depth").get<double>() - d) <= 1e-9 * d + 1e-12 * scale);
        }
        if (!x.at("contact_set").is_null()) {
          BOOST_TEST(r.at("contact_set").at("dimension") == x.at("contact_set").at("dimension"));
        }
        // Every constraint's normal is a unit vector and its force follows its gap.
        for (const auto& c : r.at("constraints")) {
          const auto& n = c.at("normal");
          BOOST_TEST(std::hypot(n[0].get<double>(), n[1].get<double>(), n[2].get<double>()) == 1.0,
                     boost::test_tools::tolerance(1e-15));
          const double f = std::hypot(c.at("force")[0].get<double>(), c.at("force")[1].get<double>(),
                                      c.at("force")[2].get<double>());
          BOOST_TEST(f == 1e9 * std::max(0.0, -c.at("gap").get<double>()), boost::test_tools::tolerance(1e-14));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(invalid_blocks_are_results) {
  // A clockwise face: that pair's result is an error naming the block, face and vertex; the
  // other pair is still computed.
  json document = cube_on_cube(1.0);
  json bad = document["pairs"][0];
  bad["id"] = "inside out";
  bad["tp"]["faces"][0] = {0, 1, 2, 3};
  document["pairs"].push_back(bad);
  const ordered_json out = run(document);
  BOOST_TEST(out.at("results")[0].at("status") == "touch");
  const auto& error = out.at("results")[1];
  BOOST_TEST(error.at("status") == "error");
  const std::string message = error.at("error");
  BOOST_TEST_INFO(message);
  BOOST_TEST(message.find("pairs[1].tp (id 'inside out')") != std::string::npos);
  BOOST_TEST(message.find("face") != std::string::npos);
  std::ostringstream summary;
  dyn::write_pairs_summary(summary, out);
  BOOST_TEST(summary.str().find("pairs: 2 (overlap 0, touch 1, separate 0, error 1)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(malformed_documents_are_named) {
  json document = cube_on_cube(1.0);
  document["H"] = 1.0;
  expect_input_error(document, "H", "unknown field; expected only dimension, kn, tolerance, policy, pairs");
  document = cube_on_cube(1.0);
  document["dimension"] = 4;
  expect_input_error(document, "dimension", "2 (polygon pairs, the default) or 3");
  document = cube_on_cube(1.0);
  document.erase("kn");
  expect_input_error(document, "kn", "N/m per constraint");
  document = cube_on_cube(1.0);
  document["tolerance"] = -1;
  expect_input_error(document, "tolerance", ">= 0");
  document = cube_on_cube(1.0);
  document["pairs"][0]["cp"]["vertices"][2] = {1, 1};
  expect_input_error(document, "pairs[0].cp.vertices[2]", "[x, y, z] triple");
  document = cube_on_cube(1.0);
  document["pairs"][0]["tp"]["faces"][1][2] = -6;
  expect_input_error(document, "pairs[0].tp.faces[1][2]", "a vertex index, an integer >= 0");
  document = cube_on_cube(1.0);
  document["pairs"][0]["tp"]["colour"] = "grey";
  expect_input_error(document, "pairs[0].tp.colour", "unknown field; expected only vertices, faces");
  dyn::PairsOverrides paper;
  paper.demarcation = rockcontact::kernel::Demarcation::paper;
  expect_input_error(cube_on_cube(1.0), "", "demarcation applies to 2D pairs", paper);
}
