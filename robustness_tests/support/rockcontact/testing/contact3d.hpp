#pragma once
// The independent contact3d reference data (robustness_tests/data/contact3d, README there):
// the input pairs of convex polyhedra and each pair's exactly computed expected result, read once.

#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/testing/json_file.hpp"

namespace rockcontact::testing {

struct Contact3dPair {
  std::string id;
  kernel::ConvexPolyhedron cp, tp;
  nlohmann::json expected;  // status, scale, volume, distance, penetration, contact_set
};

inline kernel::ConvexPolyhedron json_polyhedron(const std::string& name, const nlohmann::json& j) {
  std::vector<kernel::Point3> vertices;
  for (const auto& p : j.at("vertices")) {
    vertices.push_back({p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()});
  }
  std::vector<kernel::ConvexPolyhedron::Face> faces;
  for (const auto& f : j.at("faces")) faces.push_back(f.get<std::vector<std::uint32_t>>());
  return kernel::ConvexPolyhedron::make(name, std::move(vertices), std::move(faces));
}

// The pairs of ROCKCONTACT_TESTDATA_DIR/contact3d; fails the test when the two files do not
// match pair for pair.
inline const std::vector<Contact3dPair>& contact3d_pairs() {
  static const std::vector<Contact3dPair> pairs = [] {
    const std::string dir = std::string(ROCKCONTACT_TESTDATA_DIR) + "/contact3d";
    const nlohmann::json input = read_json(dir + "/pairs.json");
    const nlohmann::json expected = read_json(dir + "/expected.json");
    const auto& results = expected.at("results");
    BOOST_TEST_REQUIRE(input.at("dimension").get<int>() == 3);
    BOOST_TEST_REQUIRE(input.at("pairs").size() == results.size());
    std::vector<Contact3dPair> out;
    for (std::size_t i = 0; i < results.size(); ++i) {
      const auto& pair = input.at("pairs").at(i);
      const std::string id = pair.at("id").get<std::string>();
      BOOST_TEST_REQUIRE(results.at(i).at("id").get<std::string>() == id);
      out.push_back({id, json_polyhedron(id + ".cp", pair.at("cp")), json_polyhedron(id + ".tp", pair.at("tp")),
                     results.at(i)});
    }
    return out;
  }();
  return pairs;
}

}  // namespace rockcontact::testing
