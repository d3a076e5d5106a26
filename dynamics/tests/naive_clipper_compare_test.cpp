#define BOOST_TEST_MODULE naive_clipper_compare
// The worked example of examples/naive_clipper/README.md end to end: `rockcontact fuzz-cases`
// (slivers and near-parallel edges), the naive double clipper, `rockcontact pairs --compare`.
// The number of disagreements is not a reference (it is whatever the naive kernel gets wrong);
// what is checked is that the comparison exits 3 and that what it flags is right: the pairs it
// flags on status, ip_size and area are exactly those where an independent look at our exact
// results and the naive ones finds a difference, every flagged IP really differs, and at least
// one verdict differs.

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "run_command.hpp"

namespace dyn = rockcontact::dynamics;
using nlohmann::json;
using rockcontact::test::quoted;
using rockcontact::test::run_command;

namespace {

struct Run {
  dyn::PairsInput input;
  json exact;   // our results, computed here
  json naive;   // naive_clipper's
  json report;  // pairs --compare -o
  std::string text;
  int exit_status = -1;
};

const Run& run() {
  static const Run r = [] {
    const auto dir = rockcontact::test::fresh_directory("naive_clipper_compare");
    const auto cases = dir / "cases.json", naive = dir / "naive.json";
    const std::string cli = quoted(ROCKCONTACT_CLI);
    Run made;
    if (run_command(cli + " fuzz-cases --family sliver,near_parallel_ulp --count 150 --seed 1 -o " +
                    quoted(cases) + " > /dev/null") != 0 ||
        run_command(quoted(NAIVE_CLIPPER) + " " + quoted(cases) + " " + quoted(naive)) != 0) {
      return made;
    }
    made.exit_status =
        run_command(cli + " pairs --compare " + quoted(naive) + " " + quoted(cases) + " -o " +
                    quoted(dir / "report.json") + " > " + quoted(dir / "report.txt"));
    made.input = dyn::read_pairs_file(cases);
    made.exact = json(dyn::run_pairs(made.input, {rockcontact::kernel::PolicyKind::exact, {}}));
    made.naive = json::parse(rockcontact::test::read_text(naive));
    made.report = json::parse(rockcontact::test::read_text(dir / "report.json"));
    made.text = rockcontact::test::read_text(dir / "report.txt");
    return made;
  }();
  return r;
}

// The ids, in input order, of the pairs whose results satisfy `differs(exact, naive)`.
template <class Differs>
std::vector<std::string> ids_where(Differs differs) {
  std::unordered_map<std::string, const json*> naive;
  for (const json& r : run().naive.at("results")) naive.emplace(r.at("id"), &r);
  std::vector<std::string> ids;
  for (const json& ours : run().exact.at("results")) {
    const std::string& id = ours.at("id").get_ref<const std::string&>();
    if (differs(ours, *naive.at(id))) ids.push_back(id);
  }
  return ids;
}

std::vector<std::string> flagged(const std::string& field) {
  return run().report.at("fields").at(field).at("disagreeing_ids").get<std::vector<std::string>>();
}

}  // namespace

BOOST_AUTO_TEST_CASE(the_comparison_fails_with_exit_status_3) {
  BOOST_TEST_REQUIRE(run().exit_status == 3, "the commands failed or the comparison passed");
  BOOST_TEST(run().report.at("pairs") == 300);
  BOOST_TEST(run().report.at("agree") == false);
  BOOST_TEST(run().text.find("of 300 pairs disagree (status ") != std::string::npos);
  BOOST_TEST(run().report.at("fields").at("result").at("disagreements") == 0);
  BOOST_TEST(run().report.at("fields").at("force").at("compared") == 0);  // naive has none
  BOOST_TEST(run().report.at("fields").at("point").at("compared") == 0);
}

BOOST_AUTO_TEST_CASE(flagged_verdicts_are_exactly_the_differing_ones) {
  BOOST_TEST_REQUIRE(run().exit_status == 3);
  const auto differing =
      ids_where([](const json& e, const json& n) { return e.at("status") != n.at("status"); });
  BOOST_TEST(!differing.empty(), "no verdict differs: the example would show nothing");
  BOOST_TEST(flagged("status") == differing, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(flagged_vertex_counts_and_areas_are_exactly_the_differing_ones) {
  BOOST_TEST_REQUIRE(run().exit_status == 3);
  BOOST_TEST(flagged("ip_size") == ids_where([](const json& e, const json& n) {
               return e.at("ip").size() != n.at("ip").size();
             }),
             boost::test_tools::per_element());
  // The default tolerance, rtol 1e-9 relative to our area, atol 0.
  BOOST_TEST(flagged("area") == ids_where([](const json& e, const json& n) {
               const double ours = e.at("area"), theirs = n.at("area");
               return std::abs(theirs - ours) > 1e-9 * std::abs(ours);
             }),
             boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(every_flagged_ip_really_differs) {
  BOOST_TEST_REQUIRE(run().exit_status == 3);
  const auto differing =
      ids_where([](const json& e, const json& n) { return e.at("ip") != n.at("ip"); });
  for (const std::string& id : flagged("ip")) {
    const bool differs = std::find(differing.begin(), differing.end(), id) != differing.end();
    BOOST_TEST(differs, id << " flagged although its IP equals ours");
  }
}
