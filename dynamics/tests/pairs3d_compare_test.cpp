#define BOOST_TEST_MODULE pairs3d_compare
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/apps/pairs_compare.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"

// `rockcontact pairs --compare` in 3D (pairs_compare.hpp). The input, data/compare3d_in.json, is a
// 0.5 m cube over a unit cube in three closed-form positions and a pair with a clockwise face:
//   resting  base at z = 1:   touch, volume 0, contact set the square [0.25, 0.75]² at z = 1
//                              (dimension 2), four vertex-face constraints;
//   pressed  base at z = 0.9: overlap, volume 0.5 * 0.5 * 0.1 = 0.025 m³, depth 0.1 m along
//                              (0, 0, 1) (the other ways out need 0.75 m), four constraints;
//   apart    base at z = 1.5: separate, distance 0.5 m, no constraint (tolerance 0);
//   invalid  an error.
// THEIRS, data/compare3d_theirs_agree.json, holds those values typed by hand as decimals (not
// our doubles: 0.9 is not a double, so our volume and depth are a few ulps off 0.025 and 0.1),
// the results in another order, the contact set's corners from another start. Each test plants
// one error in it and checks that exactly that field of that pair disagrees, with the error the
// planted change implies.

namespace dyn = rockcontact::dynamics;
using nlohmann::json;

namespace {

const std::string data_dir = ROCKCONTACT_DYNAMICS_TESTDATA_DIR;

const dyn::PairsInput& input() {
  static const dyn::PairsInput in = dyn::read_pairs_file(data_dir + "/compare3d_in.json");
  return in;
}

json agree() { return dyn::read_json_file(data_dir + "/compare3d_theirs_agree.json"); }

json& result(json& document, const std::string& id) {
  for (json& r : document.at("results")) {
    if (r.at("id") == id) return r;
  }
  throw std::logic_error("no result " + id);
}

dyn::Comparison compare(const json& theirs, const dyn::CompareOptions& options = {}) {
  return dyn::compare_pairs(input(), dyn::parse_results(theirs, "theirs.json", 3), {}, options);
}

// The fields that disagree, each with its disagreeing ids, must be exactly `expected`.
void expect_disagreements(const dyn::Comparison& c,
                          const std::vector<std::pair<dyn::Field, std::string>>& expected) {
  for (const dyn::FieldReport& r : c.fields) {
    std::vector<std::string> ids;
    for (const auto& [field, id] : expected) {
      if (field == r.field) ids.push_back(id);
    }
    BOOST_TEST_CONTEXT("field " << dyn::to_string(r.field)) {
      BOOST_TEST(r.disagreeing_ids == ids, boost::test_tools::per_element());
    }
  }
  BOOST_TEST(c.agrees() == expected.empty());
}

// The one worst case of `field` (the planted one).
const dyn::FieldCase& planted_case(const dyn::Comparison& c, dyn::Field field) {
  const dyn::FieldReport& r = c.field(field);
  BOOST_TEST_REQUIRE(r.worst.size() >= 1u);
  return r.worst.front();
}

// The pair's size D: the bounding box of the unit cube and the cube above it, [0, 1]² x [0, 1.5].
const double resting_size = std::sqrt(1.0 + 1.0 + 1.5 * 1.5);

void expect_input_error(const json& theirs, const std::string& path, const std::string& words) {
  BOOST_TEST_CONTEXT("path " << path) {
    try {
      compare(theirs);
      BOOST_ERROR("accepted a malformed results document");
    } catch (const dyn::InputError& e) {
      BOOST_TEST(e.path() == path);
      BOOST_TEST_INFO(e.what());
      BOOST_TEST(std::string(e.what()).find(words) != std::string::npos);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(hand_values_agree) {
  const dyn::Comparison c = compare(agree());
  expect_disagreements(c, {});
  BOOST_TEST(c.dimension == 3);
  BOOST_TEST(c.pairs == 4u);
  BOOST_TEST(c.field(dyn::Field::result).compared == 4u);
  BOOST_TEST(c.field(dyn::Field::status).compared == 4u);
  for (const dyn::Field f : {dyn::Field::volume, dyn::Field::distance, dyn::Field::depth,
                             dyn::Field::contact_set, dyn::Field::constraints}) {
    BOOST_TEST(c.field(f).compared == 3u, "field " << dyn::to_string(f));
  }
  BOOST_TEST(c.field(dyn::Field::normal).compared == 1u);
  BOOST_TEST(c.field(dyn::Field::contact_dimension).compared == 1u);
  // 0.025 and 0.1 against the doubles computed from 0.9: rounding, far below rtol 1e-9.
  BOOST_TEST(c.field(dyn::Field::volume).max_rel.value() < 1e-14);
  BOOST_TEST(c.field(dyn::Field::depth).max_rel.value() < 1e-14);
  BOOST_TEST(c.field(dyn::Field::contact_set).max_abs.value() == 0.0);  // corners in any order
  BOOST_TEST(dyn::comparison_summary(c).find("compare: all 4 pairs agree; rtol 1e-09") == 0u);
}

BOOST_AUTO_TEST_CASE(ours_against_ours_has_no_error) {
  const json ours = json(dyn::run_pairs(input(), {rockcontact::kernel::PolicyKind::exact, {}}));
  const dyn::Comparison c = compare(ours);
  expect_disagreements(c, {});
  BOOST_TEST(c.fields.size() == dyn::fields3d.size());
  for (const dyn::FieldReport& r : c.fields) {
    BOOST_TEST(r.compared >= 1u);
    BOOST_TEST(r.max_abs.value_or(0.0) == 0.0);
    BOOST_TEST(r.worst.empty());
  }
}

BOOST_AUTO_TEST_CASE(a_flipped_status) {
  json theirs = agree();
  result(theirs, "resting")["status"] = "overlap";
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::status, "resting"}});
  const dyn::FieldCase& worst = planted_case(c, dyn::Field::status);
  BOOST_TEST(worst.ours == "touch");
  BOOST_TEST(worst.theirs == "overlap");
  BOOST_TEST(!worst.abs_error.has_value());
  BOOST_TEST(c.pairs_disagreeing == 1u);
}

BOOST_AUTO_TEST_CASE(a_volume_off_by_1e6_relative) {
  json theirs = agree();
  result(theirs, "pressed")["volume"] = 0.025 * (1 + 1e-6);
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::volume, "pressed"}});
  // Ours is 0.025 to a few ulps (1e-15 relative), hence the tolerance on the planted 1e-6.
  BOOST_TEST(planted_case(c, dyn::Field::volume).rel_error.value() == 1e-6,
             boost::test_tools::tolerance(1e-8));
  BOOST_TEST(planted_case(c, dyn::Field::volume).abs_error.value() == 2.5e-8,
             boost::test_tools::tolerance(1e-8));
  // The tolerance is atol + rtol * |ours|: rtol 2e-6 accepts it.
  dyn::CompareOptions loose;
  loose.rtol = 2e-6;
  BOOST_TEST(compare(theirs, loose).agrees());
}

BOOST_AUTO_TEST_CASE(a_depth_off_skips_the_normal) {
  json theirs = agree();
  result(theirs, "pressed")["penetration"]["depth"] = 0.11;
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::depth, "pressed"}});
  // 0.11 - 0.1 = 0.01 m, relative to 0.1: 0.1 (rounding of the decimals: 1e-14 at most).
  BOOST_TEST(planted_case(c, dyn::Field::depth).abs_error.value() == 0.01,
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(planted_case(c, dyn::Field::depth).rel_error.value() == 0.1,
             boost::test_tools::tolerance(1e-12));
  // The normal of a wrong depth is not compared (pairs_compare.hpp).
  BOOST_TEST(c.field(dyn::Field::normal).compared == 0u);
}

BOOST_AUTO_TEST_CASE(a_normal_rotated_by_1e3_rad) {
  json theirs = agree();
  const double angle = 1e-3;
  result(theirs, "pressed")["penetration"]["normal"] = {std::sin(angle), 0.0, std::cos(angle)};
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::normal, "pressed"}});
  // The angle to (0, 0, 1), exact up to the rounding of sin, cos and atan2 (a few ulps).
  BOOST_TEST(planted_case(c, dyn::Field::normal).abs_error.value() == angle,
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(planted_case(c, dyn::Field::normal).rel_error.value() == angle,
             boost::test_tools::tolerance(1e-12));  // the scale is 1
  // Only the direction counts, not the length.
  result(theirs, "pressed")["penetration"]["normal"] = {0.0, 0.0, 3.0};
  expect_disagreements(compare(theirs), {});
}

BOOST_AUTO_TEST_CASE(a_missing_contact_set_corner) {
  json theirs = agree();
  json& corners = result(theirs, "resting")["contact_set"]["vertices"];
  corners.erase(corners.begin());  // (0.75, 0.75, 1): 0.5 m from its nearest remaining corners
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::contact_set, "resting"}});
  BOOST_TEST(planted_case(c, dyn::Field::contact_set).abs_error.value() == 0.5);
  BOOST_TEST(planted_case(c, dyn::Field::contact_set).rel_error.value() == 0.5 / resting_size,
             boost::test_tools::tolerance(1e-15));
  BOOST_TEST(c.field(dyn::Field::contact_dimension).disagreements == 0u);
}

BOOST_AUTO_TEST_CASE(a_missing_result) {
  json theirs = agree();
  json& results = theirs["results"];
  results.erase(std::find_if(results.begin(), results.end(),
                             [](const json& r) { return r.at("id") == "apart"; }));
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::result, "apart"}});
  BOOST_TEST(planted_case(c, dyn::Field::result).theirs == "missing");
  BOOST_TEST(dyn::comparison_summary(c).find("compare: 1 of 4 pairs disagree (missing 1)") == 0u);
}

BOOST_AUTO_TEST_CASE(null_against_a_value_is_a_presence_disagreement) {
  json theirs = agree();
  result(theirs, "apart")["distance"] = nullptr;
  result(theirs, "resting")["contact_set"] = nullptr;
  result(theirs, "pressed")["penetration"] = nullptr;
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::distance, "apart"},
                           {dyn::Field::depth, "pressed"},
                           {dyn::Field::contact_set, "resting"}});
  for (const dyn::Field f : {dyn::Field::distance, dyn::Field::depth, dyn::Field::contact_set}) {
    BOOST_TEST(!planted_case(c, f).abs_error.has_value(), "field " << dyn::to_string(f));
    BOOST_TEST(planted_case(c, f).theirs.is_null());
  }
  BOOST_TEST(planted_case(c, dyn::Field::distance).ours == 0.5);
}

BOOST_AUTO_TEST_CASE(a_contact_dimension_and_constraint_count) {
  json theirs = agree();
  result(theirs, "resting")["contact_set"]["dimension"] = 1;
  result(theirs, "apart")["constraints"] = {{{"type", "vertex-vertex"}}};
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::contact_dimension, "resting"},
                           {dyn::Field::constraints, "apart"}});
  BOOST_TEST(planted_case(c, dyn::Field::contact_dimension).ours == 2);
  BOOST_TEST(planted_case(c, dyn::Field::constraints).abs_error.value() == 1.0);
}

BOOST_AUTO_TEST_CASE(values_for_an_invalid_pair_disagree_with_the_error) {
  json theirs = agree();
  result(theirs, "invalid") = {{"id", "invalid"}, {"volume", 0.0}};
  const dyn::Comparison c = compare(theirs);
  expect_disagreements(c, {{dyn::Field::status, "invalid"}});
  BOOST_TEST(planted_case(c, dyn::Field::status).theirs.is_null());
  BOOST_TEST(c.field(dyn::Field::volume).compared == 3u);  // the error pair computes nothing
}

BOOST_AUTO_TEST_CASE(malformed_results_are_input_errors) {
  json unknown = agree();
  result(unknown, "pressed")["colour"] = "red";
  expect_input_error(unknown, "results[0].colour", "unknown field");
  json unknown_inner = agree();
  result(unknown_inner, "pressed")["penetration"]["axis"] = 2;
  expect_input_error(unknown_inner, "results[0].penetration.axis", "unknown field");
  json area = agree();  // a 2D field in a 3D document
  result(area, "apart")["area"] = 0.0;
  expect_input_error(area, "results[2].area", "unknown field");
  json ghost = agree();
  ghost["results"].push_back({{"id", "ghost"}});
  expect_input_error(ghost, "results[4].id", "compare3d_in.json");
  json zero = agree();
  result(zero, "pressed")["penetration"]["normal"] = {0, 0, 0};
  expect_input_error(zero, "results[0].penetration.normal", "not all 0");
  json dimension = agree();
  result(dimension, "resting")["contact_set"]["dimension"] = 3;
  expect_input_error(dimension, "results[1].contact_set.dimension", "0, 1 or 2");
  json type = agree();
  result(type, "resting")["constraints"][1]["type"] = "face-face";
  expect_input_error(type, "results[1].constraints[1].type", "vertex-face");
}

BOOST_AUTO_TEST_CASE(the_report_shows_polyhedra) {
  json theirs = agree();
  json& corners = result(theirs, "resting")["contact_set"]["vertices"];
  corners.erase(corners.begin());
  const dyn::Comparison c = compare(theirs);
  const json report = json(dyn::comparison_json(c));
  BOOST_TEST(report.at("dimension") == 3);
  BOOST_TEST(!report.contains("demarcation"));
  BOOST_TEST(report.at("agree") == false);
  BOOST_TEST(report.at("fields").size() == dyn::fields3d.size());
  const json& worst = report.at("fields").at("contact_set").at("worst").at(0);
  BOOST_TEST(worst.at("id") == "resting");
  BOOST_TEST(worst.at("cp").at("vertices").size() == 8u);
  BOOST_TEST(worst.at("tp").at("faces").size() == 6u);
  BOOST_TEST(worst.at("tp").at("vertices").at(0) == json({0.25, 0.25, 1.0}));
  std::ostringstream text;
  dyn::write_comparison(text, c);
  BOOST_TEST_INFO(text.str());
  BOOST_TEST(text.str().find("contact_dimension") != std::string::npos);
  BOOST_TEST(text.str().find("  resting: ours [[") != std::string::npos);
  BOOST_TEST(text.str().find("\"faces\":[[0,3,2,1]") != std::string::npos);
  BOOST_TEST(text.str().find("compare: 1 of 4 pairs disagree (contact_set 1)") !=
             std::string::npos);
  BOOST_CHECK_THROW(c.field(dyn::Field::area), std::invalid_argument);
}

// The documented limit of the normal's comparison: a 0.5 m cube centred in a unit cube leaves
// along any of the six axis directions with the same depth, 0.25 + 0.5 = 0.75 m. A kernel that
// reports another of them than ours agrees on the depth and is reported as a normal
// disagreement of pi/2 rad.
BOOST_AUTO_TEST_CASE(a_tied_minimal_direction_is_a_normal_disagreement) {
  json document = dyn::read_json_file(data_dir + "/compare3d_in.json");
  json& pair = document.at("pairs").at(0);
  pair["id"] = "centred";
  for (json& v : pair.at("tp").at("vertices")) v[2] = v[2].get<double>() - 0.75;  // z 0.25..0.75
  document["pairs"] = json::array({pair});
  const dyn::PairsInput in = dyn::parse_pairs(document, "centred.json");
  const json ours = json(dyn::run_pairs(in, {rockcontact::kernel::PolicyKind::exact, {}}));
  const json& penetration = ours.at("results").at(0).at("penetration");
  BOOST_TEST_REQUIRE(penetration.at("depth").get<double>() == 0.75);
  // Another axis of the six: the normal's components moved one place, (x, y, z) -> (z, x, y).
  const json& n = penetration.at("normal");
  const json rotated = {n[2], n[0], n[1]};
  const json theirs = {
      {"results",
       {{{"id", "centred"}, {"penetration", {{"depth", 0.75}, {"normal", rotated}}}}}}};
  const dyn::Comparison c =
      dyn::compare_pairs(in, dyn::parse_results(theirs, "theirs.json", 3), {}, {});
  expect_disagreements(c, {{dyn::Field::normal, "centred"}});
  BOOST_TEST(c.field(dyn::Field::depth).disagreements == 0u);
  BOOST_TEST(planted_case(c, dyn::Field::normal).abs_error.value() == std::acos(0.0),
             boost::test_tools::tolerance(1e-15));
}
