#define BOOST_TEST_MODULE pairs_io
#include "rockcontact/dynamics/io/pairs_io.hpp"

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/apps/pairs_summary.hpp"

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;
using nlohmann::json;
using nlohmann::ordered_json;

namespace {

const std::string data_dir = ROCKCONTACT_DYNAMICS_TESTDATA_DIR;

// A valid document: two unit squares overlapping in [0.9, 1] x [0.2, 1] (the contract example).
json valid_document() {
  return json::parse(R"({"kn": 1.0e7, "H": 1.0, "pairs": [
      {"id": "p0", "cp": [[0, 0], [1, 0], [1, 1], [0, 1]],
                   "tp": [[0.9, 0.2], [1.9, 0.2], [1.9, 1.2], [0.9, 1.2]]},
      {"id": "p1", "cp": [[0, 0], [1, 0], [1, 1], [0, 1]],
                   "tp": [[0.5, 1], [1, 2], [0, 2]]}]})");
}

// Parses `document`, which must be rejected; checks the path and that the message names the
// source, the path and the expectation.
void expect_input_error(const json& document, const std::string& path,
                        const std::string& expected) {
  BOOST_TEST_CONTEXT("path " << path) {
    try {
      dyn::parse_pairs(document, "case.json");
      BOOST_ERROR("accepted a malformed document");
    } catch (const dyn::InputError& e) {
      const std::string message = e.what();
      BOOST_TEST_MESSAGE(message);
      BOOST_TEST(e.path() == path);
      BOOST_TEST(e.source() == "case.json");
      BOOST_TEST(message.find("case.json") != std::string::npos);
      BOOST_TEST(message.find(path) != std::string::npos);
      BOOST_TEST(message.find(expected) != std::string::npos,
                 "message lacks \"" << expected << '"');
    }
  }
}

// The error read_pairs_file raises for `file`, if any.
std::optional<dyn::InputError> read_error(const std::string& file) {
  try {
    dyn::read_pairs_file(file);
  } catch (const dyn::InputError& e) {
    BOOST_TEST_MESSAGE(e.what());
    return e;
  }
  return std::nullopt;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The contract pair (unit squares, TP shifted by (0.9, 0.2)), solved by hand. IP = [0.9, 1] x
// [0.2, 1], area 0.08. By the divergence theorem f = ∮ (phi_CP - phi_TP) n dL equals
// ∫∫ grad(phi_CP - phi_TP) dA over IP. In IP, d_CP = min(1 - x, 1 - y): its gradient is (-1, 0)
// except on the triangle y > x (area 0.005), where it is (0, -1); d_TP = min(x - 0.9, y - 0.2):
// gradient (1, 0) except on the triangle y - 0.2 < x - 0.9 (area 0.005), where it is (0, 1). So
// f = kn/H [(-0.075, -0.005) - (0.075, 0.005)] = (-1.5e6, -1.0e5) N/m for kn = 1e7 Pa, H = 1 m.
// Tolerance 1e-9 relative, the reference data's: the code works on the doubles nearest 0.9 and
// 0.2 (1e-16 relative from the decimals) and constructs in double (a few ulps on O(1) inputs).
void check_contract_force(const ordered_json& force) {
  const double fx = -1.5e6, fy = -1.0e5;
  const double error = std::hypot(force.at(0).get<double>() - fx, force.at(1).get<double>() - fy);
  BOOST_TEST(error <= 1e-9 * std::hypot(fx, fy), "force " << force.dump());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(parsing)

BOOST_AUTO_TEST_CASE(defaults_applied_and_values_read_as_given) {
  const dyn::PairsInput input = dyn::parse_pairs(valid_document(), "case.json");
  BOOST_TEST(input.source == "case.json");
  BOOST_TEST(input.kn == 1.0e7);
  BOOST_TEST(input.H == 1.0);
  BOOST_TEST((input.policy == kernel::PolicyKind::filtered));
  BOOST_TEST((input.demarcation == kernel::Demarcation::exact));
  BOOST_TEST_REQUIRE(input.pairs.size() == 2u);
  BOOST_TEST(input.pairs[0].id == "p0");
  BOOST_TEST_REQUIRE(input.pairs[0].tp.size() == 4u);
  // Integers and decimals are read as the doubles they denote, no tolerance needed.
  BOOST_TEST((input.pairs[0].tp[3] == kernel::Point2{0.9, 1.2}));
  BOOST_TEST((input.pairs[1].cp[2] == kernel::Point2{1.0, 1.0}));
}

BOOST_AUTO_TEST_CASE(policy_and_demarcation_read_from_the_file) {
  json document = valid_document();
  document["policy"] = "exact";
  document["demarcation"] = "paper";
  const dyn::PairsInput input = dyn::parse_pairs(document, "case.json");
  BOOST_TEST((input.policy == kernel::PolicyKind::exact));
  BOOST_TEST((input.demarcation == kernel::Demarcation::paper));
  document["policy"] = "float";
  BOOST_TEST((dyn::parse_pairs(document, "case.json").policy == kernel::PolicyKind::float_));
}

BOOST_AUTO_TEST_CASE(empty_pair_list_is_valid) {
  const dyn::PairsInput input =
      dyn::parse_pairs(json::parse(R"({"kn": 1, "H": 2, "pairs": []})"), "case.json");
  BOOST_TEST(input.pairs.empty());
}

BOOST_AUTO_TEST_CASE(document_not_an_object) {
  expect_input_error(json::array(), "", "expected a JSON object");
}

BOOST_AUTO_TEST_CASE(missing_required_fields) {
  const std::pair<const char*, const char*> top[] = {
      {"kn", "missing field; expected the normal penalty kn in Pa"},
      {"H", "missing field; expected the potential length scale H in m"},
      {"pairs", "missing field; expected an array of pairs"}};
  for (const auto& [name, expected] : top) {
    json document = valid_document();
    document.erase(name);
    expect_input_error(document, name, expected);
  }
  const std::pair<const char*, const char*> in_pair[] = {
      {"id", "missing field; expected a string"},
      {"cp", "missing field; expected the contact polygon"},
      {"tp", "missing field; expected the target polygon"}};
  for (const auto& [name, expected] : in_pair) {
    json document = valid_document();
    document["pairs"][1].erase(name);
    expect_input_error(document, std::string("pairs[1].") + name, expected);
  }
}

BOOST_AUTO_TEST_CASE(unknown_fields_rejected) {
  json document = valid_document();
  document["mu"] = 0.5;
  expect_input_error(document, "mu",
                     "unknown field; expected only dimension, kn, H, policy, demarcation, pairs");
  document = valid_document();
  document["pairs"][0]["colour"] = "red";
  expect_input_error(document, "pairs[0].colour", "unknown field; expected only id, cp, tp");
}

// A field name may hold any character (a fuzzed document had "\u0000"); the message must stay
// one C string that shows it, so what() is not cut short at the NUL.
BOOST_AUTO_TEST_CASE(control_characters_in_a_field_name_are_shown_escaped) {
  json document = valid_document();
  document["pairs"][0][std::string("co\0l\x1f\x7f", 6)] = 1;
  expect_input_error(document, "pairs[0].co\\u0000l\\u001f\\u007f", "unknown field");
  try {
    dyn::parse_pairs(document, "case.json");
  } catch (const dyn::InputError& e) {
    const std::string message = e.what();
    BOOST_TEST(message.find('\0') == std::string::npos);
    BOOST_TEST(message.ends_with("expected only id, cp, tp"));
  }
}

BOOST_AUTO_TEST_CASE(kn_and_H_must_be_finite_and_positive) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* field : {"kn", "H"}) {
    for (const json& bad : {json(0.0), json(-1.0), json(-0.0), json(inf), json(nan), json("1e7"),
                            json(true), json(nullptr), json::array({1.0})}) {
      json document = valid_document();
      document[field] = bad;
      expect_input_error(document, field, "a finite number > 0");
    }
  }
}

BOOST_AUTO_TEST_CASE(unknown_policy_or_demarcation) {
  for (const json& bad : {json("fast"), json("Exact"), json(1), json(nullptr)}) {
    json document = valid_document();
    document["policy"] = bad;
    expect_input_error(document, "policy", R"(expected one of "float", "filtered", "exact", "checked")");
    document = valid_document();
    document["demarcation"] = bad;
    expect_input_error(document, "demarcation", R"(expected one of "paper", "exact")");
  }
}

BOOST_AUTO_TEST_CASE(pairs_and_pair_shapes) {
  json document = valid_document();
  document["pairs"] = json::object();
  expect_input_error(document, "pairs", "expected an array of pairs");
  document = valid_document();
  document["pairs"][1] = json::array();
  expect_input_error(document, "pairs[1]", "expected a pair, an object");
  document = valid_document();
  document["pairs"][0]["id"] = 7;
  expect_input_error(document, "pairs[0].id",
                     "expected a string, unique within the file, got number 7");
  document = valid_document();
  document["pairs"][0]["cp"] = "square";
  expect_input_error(document, "pairs[0].cp",
                     "expected the contact polygon, an array of [x, y] vertices");
}

BOOST_AUTO_TEST_CASE(polygon_vertices_must_be_number_pairs) {
  for (const json& bad :
       {json::array({2.0}), json::array({1.0, 2.0, 3.0}), json::array({1.0, "2"}),
        json::object({{"x", 1.0}, {"y", 2.0}}), json(1.0), json::array({nullptr, 1.0})}) {
    json document = valid_document();
    document["pairs"][1]["tp"][2] = bad;
    expect_input_error(document, "pairs[1].tp[2]", "expected a vertex, an [x, y] pair of numbers");
  }
}

BOOST_AUTO_TEST_CASE(duplicate_ids_rejected) {
  json document = valid_document();
  document["pairs"].push_back(document["pairs"][0]);
  expect_input_error(document, "pairs[2].id", "duplicate id \"p0\" (also pairs[0].id)");
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(reading_files)

BOOST_AUTO_TEST_CASE(malformed_json_reports_line_and_column) {
  const auto e = read_error(data_dir + "/bad_syntax.json");
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST(e->path().empty());
  BOOST_TEST(contains(e->what(), "bad_syntax.json"));
  BOOST_TEST(contains(e->what(), "malformed JSON"));
  // The missing comma ends line 3; the parser notices at the next token, on line 4.
  BOOST_TEST(contains(e->what(), "line 4, column"));
}

BOOST_AUTO_TEST_CASE(number_overflow_names_the_literal) {
  const auto e = read_error(data_dir + "/number_overflow.json");
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST(contains(e->what(), "number_overflow.json"));
  BOOST_TEST(contains(e->what(), "1e400"));
}

BOOST_AUTO_TEST_CASE(bad_vertex_in_a_file_names_file_and_field) {
  const auto e = read_error(data_dir + "/bad_vertex.json");
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST(e->path() == "pairs[1].tp[2]");
  BOOST_TEST(contains(e->what(), "bad_vertex.json: pairs[1].tp[2]: expected a vertex"));
}

BOOST_AUTO_TEST_CASE(missing_file) {
  const auto e = read_error(data_dir + "/no_such_file.json");
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST(contains(e->what(), "cannot open"));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(running)

// The contract example against its hand solution (check_contract_force).
BOOST_AUTO_TEST_CASE(contract_example_matches_hand_solution) {
  const ordered_json out = dyn::run_pairs(dyn::parse_pairs(valid_document(), "case.json"));
  const ordered_json& r = out.at("results").at(0);
  BOOST_TEST(r.at("id") == "p0");
  BOOST_TEST(r.at("status") == "overlap");
  BOOST_TEST(std::abs(r.at("area").get<double>() - 0.08) <= 1e-9 * 0.08);
  check_contract_force(r.at("force"));
  BOOST_TEST(r.at("point").is_array());
  // Every IP vertex is an input vertex or the crossing of two axis-parallel edges, all of them
  // exactly representable: the rectangle's corners must appear exactly, CCW from any start.
  const std::vector<std::vector<double>> rectangle = {
      {0.9, 0.2}, {1.0, 0.2}, {1.0, 1.0}, {0.9, 1.0}};
  const auto ip = r.at("ip").get<std::vector<std::vector<double>>>();
  BOOST_TEST_REQUIRE(ip.size() == 4u);
  std::size_t start = 0;
  while (start < 4 && ip[start] != rectangle[0]) ++start;
  BOOST_TEST_REQUIRE(start < 4u);
  for (std::size_t k = 0; k < 4; ++k) BOOST_TEST((ip[(start + k) % 4] == rectangle[k]));
}

BOOST_AUTO_TEST_CASE(output_document_layout) {
  const ordered_json out = dyn::run_pairs(dyn::parse_pairs(valid_document(), "case.json"));
  std::vector<std::string> keys;
  for (const auto& [key, value] : out.items()) keys.push_back(key);
  BOOST_TEST((keys == std::vector<std::string>{"policy", "demarcation", "results", "stats"}));
  BOOST_TEST(out.at("policy") == "filtered");
  BOOST_TEST(out.at("demarcation") == "exact");
  keys.clear();
  for (const auto& [key, value] : out.at("results").at(0).items()) keys.push_back(key);
  BOOST_TEST((keys == std::vector<std::string>{"id", "status", "ip", "area", "force", "point",
                                               "fallbacks"}));
  // Pair p1: the triangle's vertex (0.5, 1) lies exactly on the square's top edge.
  const ordered_json& touch = out.at("results").at(1);
  BOOST_TEST(touch.at("status") == "touch");
  BOOST_TEST(touch.at("ip").empty());
  BOOST_TEST(touch.at("area") == 0.0);
  BOOST_TEST((touch.at("force") == ordered_json::array({0.0, 0.0})));
  BOOST_TEST(touch.at("point").is_null());
  const ordered_json& stats = out.at("stats");
  BOOST_TEST(stats.at("pairs") == 2);
  BOOST_TEST(stats.at("predicates").get<std::uint64_t>() >=
             stats.at("fallbacks").get<std::uint64_t>());
  BOOST_TEST(stats.at("seconds").get<double>() >= 0.0);
}

BOOST_AUTO_TEST_CASE(doubles_round_trip_through_text) {
  const ordered_json out = dyn::run_pairs(dyn::parse_pairs(valid_document(), "case.json"));
  const ordered_json back = ordered_json::parse(out.dump(2));
  const auto& a = out.at("results").at(0);
  const auto& b = back.at("results").at(0);
  for (const char* field : {"force", "point", "ip"}) BOOST_TEST((a.at(field) == b.at(field)));
  BOOST_TEST(a.at("area").get<double>() == b.at("area").get<double>());
}

BOOST_AUTO_TEST_CASE(overrides_win_over_the_file) {
  json document = valid_document();
  document["policy"] = "float";
  document["demarcation"] = "paper";
  const dyn::PairsInput input = dyn::parse_pairs(document, "case.json");
  const ordered_json from_file = dyn::run_pairs(input);
  BOOST_TEST(from_file.at("policy") == "float");
  BOOST_TEST(from_file.at("demarcation") == "paper");
  dyn::PairsOverrides overrides;
  overrides.policy = kernel::PolicyKind::exact;
  overrides.demarcation = kernel::Demarcation::exact;
  const ordered_json overridden = dyn::run_pairs(input, overrides);
  BOOST_TEST(overridden.at("policy") == "exact");
  BOOST_TEST(overridden.at("demarcation") == "exact");
  check_contract_force(overridden.at("results").at(0).at("force"));
}

BOOST_AUTO_TEST_CASE(invalid_polygons_are_reported_per_pair) {
  json document = valid_document();
  // pairs[2]: CP repeats vertex 0 at index 2; pairs[3]: TP is the contract TP listed clockwise.
  document["pairs"].push_back(json::parse(R"({"id": "repeated",
      "cp": [[0, 0], [1, 0], [0, 0], [0, 1]], "tp": [[0.5, 0.5], [2, 0.5], [2, 2]]})"));
  document["pairs"].push_back(json::parse(R"({"id": "clockwise",
      "cp": [[0, 0], [1, 0], [1, 1], [0, 1]],
      "tp": [[0.9, 0.2], [0.9, 1.2], [1.9, 1.2], [1.9, 0.2]]})"));
  document["pairs"].push_back(valid_document()["pairs"][0]);
  document["pairs"][4]["id"] = "after";
  const ordered_json out = dyn::run_pairs(dyn::parse_pairs(document, "case.json"));
  const ordered_json& results = out.at("results");
  BOOST_TEST_REQUIRE(results.size() == 5u);

  const ordered_json& repeated = results[2];
  BOOST_TEST(repeated.at("id") == "repeated");
  BOOST_TEST(repeated.at("status") == "error");
  const std::string repeated_message = repeated.at("error").get<std::string>();
  BOOST_TEST_MESSAGE(repeated_message);
  BOOST_TEST(contains(repeated_message, "pairs[2].cp"));
  BOOST_TEST(contains(repeated_message, "id 'repeated'"));
  BOOST_TEST(contains(repeated_message, "vertex 2"));

  const ordered_json& clockwise = results[3];
  BOOST_TEST(clockwise.at("status") == "error");
  const std::string clockwise_message = clockwise.at("error").get<std::string>();
  BOOST_TEST_MESSAGE(clockwise_message);
  BOOST_TEST(contains(clockwise_message, "pairs[3].tp"));
  BOOST_TEST(contains(clockwise_message, "clockwise"));

  // The pairs around the errors are computed as if alone.
  const ordered_json alone = dyn::run_pairs(dyn::parse_pairs(valid_document(), "case.json"));
  BOOST_TEST(results[0].at("status") == "overlap");
  BOOST_TEST((results[0].at("force") == alone.at("results")[0].at("force")));
  BOOST_TEST(results[1].at("status") == "touch");
  BOOST_TEST(results[4].at("id") == "after");
  BOOST_TEST((results[4].at("force") == alone.at("results")[0].at("force")));
  BOOST_TEST(out.at("stats").at("pairs") == 5);
}

// The shipped example: statuses are known by construction (see examples/pairs/README.md).
BOOST_AUTO_TEST_CASE(shipped_example_statuses) {
  const ordered_json out = dyn::run_pairs(
      dyn::read_pairs_file(std::string(ROCKCONTACT_EXAMPLES_DIR) + "/pairs/basic.json"));
  std::vector<std::string> statuses;
  for (const auto& r : out.at("results")) statuses.push_back(r.at("status").get<std::string>());
  BOOST_TEST((statuses == std::vector<std::string>{"overlap", "overlap", "touch", "separate",
                                                   "overlap", "error"}));
  check_contract_force(out.at("results")[0].at("force"));  // "squares" is the contract pair
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(summary)

// A hand-written output document, so the expected totals are counted by hand.
BOOST_AUTO_TEST_CASE(table_rows_and_totals) {
  const ordered_json document = ordered_json::parse(R"({
    "policy": "exact", "demarcation": "paper",
    "results": [
      {"id": "a", "status": "overlap", "ip": [[0, 0], [1, 0], [0, 1]], "area": 0.5,
       "force": [3.0, -4.0], "point": [0.25, 0.5], "fallbacks": 2},
      {"id": "b", "status": "separate", "ip": [], "area": 0.0, "force": [0.0, 0.0],
       "point": null, "fallbacks": 0},
      {"id": "long-identifier", "status": "error", "error": "polygon pairs[2].cp: bad"}],
    "stats": {"pairs": 3, "predicates": 10, "fallbacks": 2, "seconds": 3e-6}})");
  std::ostringstream text;
  dyn::write_pairs_summary(text, document);
  const std::string s = text.str();
  BOOST_TEST_MESSAGE(s);
  BOOST_TEST(contains(s, "policy exact, demarcation paper"));
  BOOST_TEST(contains(s, "(3, -4)"));      // force components
  BOOST_TEST(contains(s, " 5 "));          // |(3, -4)| = 5
  BOOST_TEST(contains(s, "(0.25, 0.5)"));  // point
  BOOST_TEST(contains(s, "long-identifier  error     polygon pairs[2].cp: bad"));
  BOOST_TEST(contains(s, "pairs: 3 (overlap 1, touch 0, separate 1, error 1)"));
  BOOST_TEST(contains(s, "predicates: 10, exact fallbacks: 2 (20 % of predicates)"));
  BOOST_TEST(contains(s, "1000 ns per pair"));  // 3e-6 s / 3 pairs
}

BOOST_AUTO_TEST_SUITE_END()
