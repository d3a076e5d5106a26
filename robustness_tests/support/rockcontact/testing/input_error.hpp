#pragma once
// The checks of the scene readers' error messages (2D, 3D, CDEM): a malformed document must be
// refused with an InputError naming its source, the JSON path of the field and what was expected;
// a file that is not JSON, with the file and the line.

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rockcontact/dynamics/io/pairs_io.hpp"

namespace rockcontact::testing {

// `parse(document, "case.json")` must throw an InputError whose message starts with
// "case.json: <path>: " and contains `expected`.
template <class Parse>
void expect_input_error(Parse&& parse, const nlohmann::json& document, const std::string& path,
                        const std::string& expected) {
  BOOST_TEST_CONTEXT("path " << path) {
    try {
      parse(document, "case.json");
      BOOST_ERROR("accepted a malformed scene");
    } catch (const dynamics::InputError& e) {
      const std::string message = e.what();
      BOOST_TEST_MESSAGE(message);
      BOOST_TEST(e.source() == "case.json");
      BOOST_TEST(e.path() == path);
      BOOST_TEST(message.find("case.json: " + path + ": ") == 0);
      BOOST_TEST(message.find(expected) != std::string::npos,
                 "message lacks \"" << expected << '"');
    }
  }
}

// `read(file)` of a temporary file `name` holding `text`, JSON with a syntax error on its line 2,
// must throw an InputError naming the file and no JSON path, saying "malformed JSON" and the line.
template <class Read>
void expect_malformed_json(Read&& read, const std::string& name, const std::string& text) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / name;
  std::ofstream(file) << text;
  try {
    read(file);
    BOOST_ERROR("accepted malformed JSON");
  } catch (const dynamics::InputError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(e.path().empty());
    BOOST_TEST(std::string(e.what()).find(file.string() + ": malformed JSON: ") == 0);
    BOOST_TEST(std::string(e.what()).find("line 2") != std::string::npos);
  }
  std::filesystem::remove(file);
}

}  // namespace rockcontact::testing
