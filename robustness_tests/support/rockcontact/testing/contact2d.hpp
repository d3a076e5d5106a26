#pragma once
// The independent contact2d reference data (robustness_tests/data/contact2d, README there):
// the input pairs with kn and H, and each pair's exactly computed expected result, read once.

#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/testing/json_file.hpp"

namespace rockcontact::testing {

struct Contact2dPair {
  std::string id;
  std::vector<kernel::Point2> cp, tp;  // as given, m
  nlohmann::json expected;             // status, ip, area, force, point, size
};

struct Contact2dData {
  double kn = 0.0;  // Pa
  double H = 0.0;   // m
  std::vector<Contact2dPair> pairs;
};

inline std::vector<kernel::Point2> json_points(const nlohmann::json& j) {
  std::vector<kernel::Point2> out;
  for (const auto& p : j) out.push_back({p.at(0).get<double>(), p.at(1).get<double>()});
  return out;
}

// The data of ROCKCONTACT_TESTDATA_DIR/contact2d; fails the test when the two files do not
// match pair for pair or the expected results are not for the exact demarcation.
inline const Contact2dData& contact2d_data() {
  static const Contact2dData data = [] {
    const std::string dir = std::string(ROCKCONTACT_TESTDATA_DIR) + "/contact2d";
    const nlohmann::json input = read_json(dir + "/pairs.json");
    const nlohmann::json expected = read_json(dir + "/expected.json");
    BOOST_TEST_REQUIRE(expected.at("demarcation").get<std::string>() == "exact");
    const auto& results = expected.at("results");
    BOOST_TEST_REQUIRE(input.at("pairs").size() == results.size());
    Contact2dData d{input.at("kn").get<double>(), input.at("H").get<double>(), {}};
    for (std::size_t i = 0; i < results.size(); ++i) {
      const auto& pair = input.at("pairs").at(i);
      const std::string id = pair.at("id").get<std::string>();
      BOOST_TEST_REQUIRE(results.at(i).at("id").get<std::string>() == id);
      d.pairs.push_back({id, json_points(pair.at("cp")), json_points(pair.at("tp")), results.at(i)});
    }
    return d;
  }();
  return data;
}

}  // namespace rockcontact::testing
