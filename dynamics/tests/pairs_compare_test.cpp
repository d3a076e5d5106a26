#define BOOST_TEST_MODULE pairs_compare
#include "rockcontact/dynamics/apps/pairs_compare.hpp"

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;
namespace rb = rockcontact::robustness;
using nlohmann::json;

namespace {

// The six pairs of examples/pairs/basic.json (three overlaps, a touch, a separation and a
// clockwise polygon) and a few generated near-degenerate pairs, with our exact results.
struct Base {
  dyn::PairsInput input;
  json ours;  // run_pairs under Exact
};

const Base& base() {
  static const Base b = [] {
    Base made;
    made.input = dyn::read_pairs_file(std::string(ROCKCONTACT_EXAMPLES_DIR) + "/pairs/basic.json");
    for (const rb::Family family : {rb::Family::sliver, rb::Family::near_parallel_ulp,
                                    rb::Family::vertex_on_edge, rb::Family::nested}) {
      for (std::uint64_t i = 0; i < 2; ++i) {
        const rb::PolygonPair pair = rb::generate_pair(family, 7, i);
        made.input.pairs.push_back(
            {std::string(rb::to_string(family)) + "-" + std::to_string(i), pair.cp, pair.tp});
      }
    }
    made.ours = json(dyn::run_pairs(made.input, {kernel::PolicyKind::exact, std::nullopt}));
    return made;
  }();
  return b;
}

json& result(json& document, const std::string& id) {
  for (json& r : document.at("results")) {
    if (r.at("id") == id) return r;
  }
  throw std::logic_error("no result " + id);
}

dyn::Comparison compare(const json& theirs, const dyn::CompareOptions& options = {}) {
  return dyn::compare_pairs(base().input, dyn::parse_results(theirs, "theirs.json"), {}, options);
}

// The tolerated perturbations, which must not be flagged: an area 1e-12 off relative to itself,
// a point moved by 1e-12 m (the pair's size is ~2 m).
void perturb_within_tolerance(json& theirs) {
  result(theirs, "triangle-corner")["area"] =
      result(theirs, "triangle-corner")["area"].get<double>() * (1 + 1e-12);
  result(theirs, "squares")["point"][0] =
      result(theirs, "squares")["point"][0].get<double>() + 1e-12;
}

// Ours with one planted error per field (and fields absent everywhere: fallbacks, stats,
// policy), plus the tolerated perturbations.
json planted() {
  json theirs = base().ours;
  theirs.erase("stats");
  theirs.erase("policy");
  for (json& r : theirs["results"]) r.erase("fallbacks");
  result(theirs, "vertex-on-edge")["status"] = "overlap";  // a flipped verdict (touch)
  json& squares_area = result(theirs, "squares")["area"];
  squares_area = squares_area.get<double>() * (1 + 1e-3);  // a relative 1e-3
  json& force = result(theirs, "chamfer")["force"];
  force = {force[0].get<double>() + 3.0, force[1].get<double>() - 4.0};  // |(3, -4)| = 5 N/m
  result(theirs, "triangle-corner")["point"] = nullptr;                  // a point removed
  json& ip = result(theirs, "chamfer")["ip"];
  ip.erase(ip.begin());  // a vertex dropped
  json& results = theirs["results"];
  results.erase(std::find_if(results.begin(), results.end(),
                             [](const json& r) { return r.at("id") == "separate"; }));  // missing
  perturb_within_tolerance(theirs);
  return theirs;
}

void check_field(const dyn::Comparison& c, dyn::Field field, std::size_t compared,
                 const std::vector<std::string>& ids) {
  const dyn::FieldReport& r = c.field(field);
  BOOST_TEST_CONTEXT("field " << dyn::to_string(field)) {
    BOOST_TEST(r.compared == compared);
    BOOST_TEST(r.disagreements == ids.size());
    BOOST_TEST(r.disagreeing_ids == ids, boost::test_tools::per_element());
  }
}

double diagonal(const dyn::PairSpec& pair) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto* polygon : {&pair.cp, &pair.tp}) {
    for (const kernel::Point2& p : *polygon) {
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    }
  }
  return std::hypot(x1 - x0, y1 - y0);
}

const dyn::PairSpec& pair(const std::string& id) {
  return *std::find_if(base().input.pairs.begin(), base().input.pairs.end(),
                       [&](const dyn::PairSpec& p) { return p.id == id; });
}

// The distance from ours's first chamfer IP vertex (the dropped one) to the nearest other.
double dropped_vertex_distance() {
  const json& ip = result(const_cast<json&>(base().ours), "chamfer").at("ip");
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < ip.size(); ++i) {
    nearest = std::min(nearest, std::hypot(ip[i][0].get<double>() - ip[0][0].get<double>(),
                                           ip[i][1].get<double>() - ip[0][1].get<double>()));
  }
  return nearest;
}

void expect_input_error(const json& theirs, const std::string& path, const std::string& part) {
  BOOST_TEST_CONTEXT("path " << path) {
    try {
      compare(theirs);
      BOOST_ERROR("accepted a malformed results document");
    } catch (const dyn::InputError& e) {
      BOOST_TEST_MESSAGE(e.what());
      BOOST_TEST(e.source() == "theirs.json");
      BOOST_TEST(e.path() == path);
      BOOST_TEST(std::string(e.what()).find(part) != std::string::npos, "lacks \"" << part << '"');
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(finds_exactly_the_planted_errors) {
  const dyn::Comparison c = compare(planted());
  const std::size_t n = base().input.pairs.size();  // 14; "separate" missing, "clockwise" error
  check_field(c, dyn::Field::result, n, {"separate"});
  check_field(c, dyn::Field::status, n - 1, {"vertex-on-edge"});
  check_field(c, dyn::Field::ip_size, n - 2, {"chamfer"});
  check_field(c, dyn::Field::ip, n - 2, {"chamfer"});
  check_field(c, dyn::Field::area, n - 2, {"squares"});
  check_field(c, dyn::Field::force, n - 2, {"chamfer"});
  check_field(c, dyn::Field::point, n - 2, {"triangle-corner"});
  BOOST_TEST(c.pairs == n);
  BOOST_TEST(c.pairs_disagreeing == 5u);
  BOOST_TEST(!c.agrees());          // the CLI exits 3
  BOOST_TEST(c.policy == "exact");  // the file says "filtered": compare mode ignores it
}

// Each maximum is the planted amount up to the rounding of planting it: a double near a (~0.1)
// times (1 + 1e-3) is off by half an ulp, ~1e-13 of the 1e-3; 3 and 4 added to ~2.5e4 are off
// by ulp(2.5e4) ~ 4e-12; 1e-12 added to 0.95 by ulp(0.95) ~ 1e-16. Differences of doubles
// within a factor 2 of each other are exact (Sterbenz), so nothing else rounds.
BOOST_AUTO_TEST_CASE(maximum_errors_are_the_planted_amounts) {
  const dyn::Comparison c = compare(planted());
  const auto& area = c.field(dyn::Field::area);
  BOOST_TEST(area.max_rel.value() == 1e-3, boost::test_tools::tolerance(1e-12));
  const auto& force = c.field(dyn::Field::force);
  BOOST_TEST(std::abs(force.max_abs.value() - 5.0) <= 1e-10);
  const auto& point = c.field(dyn::Field::point);
  BOOST_TEST(std::abs(point.max_abs.value() - 1e-12) <= 2e-16);
  BOOST_TEST(point.max_rel.value() == point.max_abs.value() / diagonal(pair("squares")),
             boost::test_tools::tolerance(1e-12));
  const auto& ip = c.field(dyn::Field::ip);
  BOOST_TEST(ip.max_abs.value() == dropped_vertex_distance());
  BOOST_TEST(ip.max_rel.value() == dropped_vertex_distance() / diagonal(pair("chamfer")));
  BOOST_TEST(c.field(dyn::Field::ip_size).max_abs.value() == 1.0);
}

BOOST_AUTO_TEST_CASE(worst_cases_put_disagreements_first) {
  dyn::CompareOptions options;
  options.worst = 5;
  const dyn::Comparison c = compare(planted(), options);
  const auto& area = c.field(dyn::Field::area).worst;
  BOOST_TEST_REQUIRE(area.size() == 2u);  // the planted error, then the tolerated one
  BOOST_TEST(area[0].pair.id == "squares");
  BOOST_TEST(area[0].disagrees);
  BOOST_TEST(area[1].pair.id == "triangle-corner");
  BOOST_TEST(!area[1].disagrees);
  BOOST_TEST((area[0].pair.cp == pair("squares").cp));
  const auto& point = c.field(dyn::Field::point).worst;
  BOOST_TEST_REQUIRE(point.size() == 2u);
  BOOST_TEST(point[0].pair.id == "triangle-corner");  // null against a value: no number
  BOOST_TEST(point[0].theirs.is_null());
  BOOST_TEST(!point[0].abs_error.has_value());
  options.worst = 1;
  BOOST_TEST(compare(planted(), options).field(dyn::Field::area).worst.size() == 1u);
}

BOOST_AUTO_TEST_CASE(perturbations_within_tolerance_agree) {
  json theirs = base().ours;
  perturb_within_tolerance(theirs);
  const dyn::Comparison c = compare(theirs);
  BOOST_TEST(c.agrees());
  BOOST_TEST(c.field(dyn::Field::area).max_rel.value() == 1e-12,
             boost::test_tools::tolerance(1e-3));
  BOOST_TEST(dyn::comparison_summary(c).find("compare: all 14 pairs agree") == 0u);
}

BOOST_AUTO_TEST_CASE(ours_against_ours_has_no_error) {
  const dyn::Comparison c = compare(base().ours);
  BOOST_TEST(c.agrees());
  for (const dyn::FieldReport& r : c.fields) {
    BOOST_TEST(r.compared >= base().input.pairs.size() - 1);
    BOOST_TEST(r.max_abs.value_or(0.0) == 0.0);
    BOOST_TEST(r.worst.empty());
  }
}

BOOST_AUTO_TEST_CASE(fields_absent_everywhere_are_not_compared) {
  json theirs = base().ours;
  for (const char* name : {"stats", "policy", "demarcation"}) theirs.erase(name);
  for (json& r : theirs["results"]) {
    for (const char* name : {"force", "point", "fallbacks"}) r.erase(name);
  }
  const dyn::Comparison c = compare(theirs);
  BOOST_TEST(c.field(dyn::Field::force).compared == 0u);
  BOOST_TEST(c.field(dyn::Field::point).compared == 0u);
  BOOST_TEST(c.field(dyn::Field::area).compared == base().input.pairs.size() - 1);
  BOOST_TEST(c.agrees());
  BOOST_TEST(dyn::comparison_summary(c).find("not compared: force, point") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(only_an_id_is_required) {
  json theirs = {{"results", json::array()}};
  for (const dyn::PairSpec& p : base().input.pairs) theirs["results"].push_back({{"id", p.id}});
  const dyn::Comparison c = compare(theirs);
  BOOST_TEST(c.agrees());
  BOOST_TEST(c.field(dyn::Field::result).compared == base().input.pairs.size());
  BOOST_TEST(c.field(dyn::Field::status).compared == 0u);
}

// An error agrees only with an error; when one side is an error only the verdict is compared,
// and values given without a status for polygons we refuse disagree on it.
BOOST_AUTO_TEST_CASE(error_results) {
  json theirs = base().ours;
  result(theirs, "squares") = {{"id", "squares"}, {"status", "error"}, {"error", "bad polygon"}};
  result(theirs, "clockwise") = {{"id", "clockwise"}, {"area", 0.08}};
  const dyn::Comparison c = compare(theirs);
  check_field(c, dyn::Field::status, base().input.pairs.size(), {"squares", "clockwise"});
  check_field(c, dyn::Field::area, base().input.pairs.size() - 2, {});
  const auto& worst = c.field(dyn::Field::status).worst;
  BOOST_TEST_REQUIRE(worst.size() == 2u);
  BOOST_TEST(worst[0].ours == "overlap");
  BOOST_TEST(worst[0].theirs == "error");
  BOOST_TEST(worst[1].ours == "error");
  BOOST_TEST(worst[1].theirs.is_null());
}

// numpy's rule: error > atol + rtol * scale disagrees; a zero of ours matches only zero unless
// atol allows more; the relative error of a non-zero against zero is infinite.
BOOST_AUTO_TEST_CASE(tolerances) {
  json theirs = base().ours;
  result(theirs, "squares")["area"] = result(theirs, "squares")["area"].get<double>() * (1 + 1e-3);
  result(theirs, "vertex-on-edge")["area"] = 1e-20;
  dyn::CompareOptions options;
  check_field(compare(theirs, options), dyn::Field::area, 13, {"squares", "vertex-on-edge"});
  BOOST_TEST(std::isinf(compare(theirs, options).field(dyn::Field::area).max_rel.value()));
  options.rtol = 2e-3;
  check_field(compare(theirs, options), dyn::Field::area, 13, {"vertex-on-edge"});
  options.atol = 1e-19;
  BOOST_TEST(compare(theirs, options).agrees());
  const json report = json(dyn::comparison_json(compare(theirs, {})));
  BOOST_TEST(report.at("fields").at("area").at("max_rel") == "inf");
  BOOST_TEST(report.at("agree") == false);
}

BOOST_AUTO_TEST_CASE(report_json_and_text) {
  const dyn::Comparison c = compare(planted());
  const json report = json(dyn::comparison_json(c));
  BOOST_TEST(report.at("pairs") == 14);
  BOOST_TEST(report.at("pairs_disagreeing") == 5);
  BOOST_TEST(report.at("fields").at("force").at("disagreeing_ids") == json::array({"chamfer"}));
  const json& worst = report.at("fields").at("status").at("worst").at(0);
  BOOST_TEST(worst.at("id") == "vertex-on-edge");
  BOOST_TEST(worst.at("ours") == "touch");
  BOOST_TEST(worst.at("theirs") == "overlap");
  BOOST_TEST(worst.at("tp").size() == 3u);
  std::ostringstream text;
  dyn::write_comparison(text, c);
  BOOST_TEST(text.str().find("vertex-on-edge: ours \"touch\", theirs \"overlap\"  DISAGREES") !=
             std::string::npos);
  BOOST_TEST(dyn::comparison_summary(c) ==
             "compare: 5 of 14 pairs disagree (missing 1, status 1, ip_size 1, ip 1, area 1, "
             "force 1, point 1); rtol 1e-09, atol 0");
}

BOOST_AUTO_TEST_CASE(malformed_results_are_input_errors) {
  json theirs = base().ours;
  result(theirs, "squares")["id"] = "no-such-pair";
  expect_input_error(theirs, "results[0].id", "expected the id of a pair of");
  theirs = base().ours;
  result(theirs, "squares")["id"] = "separate";
  expect_input_error(theirs, "results[3].id", "duplicate id \"separate\" (also results[0].id)");
  theirs = base().ours;
  result(theirs, "squares")["colour"] = "red";
  expect_input_error(theirs, "results[0].colour", "unknown field; expected only id, status");
  theirs = base().ours;
  theirs["version"] = 2;
  expect_input_error(theirs, "version", "unknown field; expected only policy, demarcation");
  theirs = base().ours;
  result(theirs, "squares")["error"] = "oops";
  expect_input_error(theirs, "results[0].error", "\"status\": \"error\"");
  theirs = base().ours;
  result(theirs, "clockwise")["area"] = 0.0;
  expect_input_error(theirs, "results[5].area", "unknown field; expected only id, status, error");
  theirs = base().ours;
  result(theirs, "squares")["status"] = "overlapping";
  expect_input_error(theirs, "results[0].status", "expected one of \"separate\"");
  theirs = base().ours;
  result(theirs, "squares")["point"] = "none";
  expect_input_error(theirs, "results[0].point", "or null, got string \"none\"");
  theirs = base().ours;
  theirs["stats"]["pairs"] = -1;
  expect_input_error(theirs, "stats.pairs", "an integer >= 0");
  theirs = base().ours;
  theirs.erase("results");
  expect_input_error(theirs, "results", "missing field");
}
