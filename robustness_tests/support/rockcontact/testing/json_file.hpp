#pragma once
// A test's JSON reference file, read whole; a file that cannot be opened fails the test with its
// name (and malformed JSON with nlohmann's parse error) instead of comparing against nothing.

#include <boost/test/unit_test.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace rockcontact::testing {

inline nlohmann::json read_json(const std::string& file) {
  std::ifstream stream(file);
  BOOST_TEST_REQUIRE(stream.good(), "cannot open " << file);
  return nlohmann::json::parse(stream);
}

}  // namespace rockcontact::testing
