#define BOOST_TEST_MODULE validation
#include "rockcontact/dynamics/apps/validation.hpp"

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) result.push_back(line);
  return result;
}

// Display column of `part` in `line`, counting UTF-8 code points.
std::size_t column(const std::string& line, const std::string& part) {
  const std::size_t at = line.find(part);
  std::size_t width = 0;
  for (std::size_t i = 0; i < at; ++i) {
    width += (static_cast<unsigned char>(line[i]) & 0xC0) != 0x80 ? 1 : 0;
  }
  return width;
}

}  // namespace

// The table a script reads: a header, one row per check with its verdict, aligned columns
// even with multi-byte names ("°"), and the count of failures.
BOOST_AUTO_TEST_CASE(table_lists_every_check_with_its_verdict) {
  const std::vector<dyn::ValidationRow> rows{
      {"4.3 incline phi=20°", "slide l vs eq. 30", "0.9064 m", "0.9679 m", 0.068,
       dyn::Bound::at_most, 0.01, 0.28, false},
      {"5.1 bounce", "max |dy|", ">= 1 mm", "0.08 m", 0.08, dyn::Bound::at_least, 1e-3, 0.02,
       true}};
  std::ostringstream out;
  dyn::write_validation_table(out, rows);
  BOOST_TEST_MESSAGE(out.str());
  const auto text = lines(out.str());
  BOOST_TEST_REQUIRE(text.size() == 4u);
  for (const char* name :
       {"scene", "check", "reference", "measured", "error", "tolerance", "wall s", "result"}) {
    BOOST_TEST(text[0].find(name) != std::string::npos, "header lacks " << name);
  }
  BOOST_TEST(text[1].find("FAIL") != std::string::npos);
  BOOST_TEST(text[1].find("<= 0.01") != std::string::npos);
  BOOST_TEST(text[2].find("PASS") != std::string::npos);
  BOOST_TEST(text[2].find(">= 0.001") != std::string::npos);
  BOOST_TEST(column(text[1], "slide") == column(text[0], "check"));
  BOOST_TEST(column(text[1], "FAIL") == column(text[0], "result"));
  BOOST_TEST(column(text[2], "PASS") == column(text[0], "result"));
  BOOST_TEST(text[3] == "2 checks, 1 failed");
}

BOOST_AUTO_TEST_CASE(missing_scene_file_names_it) {
  dyn::ValidationOptions options;
  options.scenes_dir = fs::current_path() / "no_such_scene_directory";
  options.quick = true;
  try {
    dyn::run_validation(options);
    BOOST_ERROR("ran without its scenes");
  } catch (const dyn::InputError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(std::string(e.what()).find("collision_squares.json: cannot open") !=
               std::string::npos);
  }
}

// The quick run of the shipped scenes: every paper scene has its rows, each row is complete
// and its verdict follows from its numbers. Whether they pass is the CLI test's business
// (dynamics_cli_validate_quick), so that a physics miss shows there with the whole table.
BOOST_AUTO_TEST_CASE(quick_run_covers_every_scene_with_consistent_rows) {
  dyn::ValidationOptions options;
  options.scenes_dir = ROCKCONTACT_EXAMPLES_DIR "/scenes";
  options.quick = true;
  options.out_dir = fs::current_path() / "validation_test_out";
  fs::remove_all(options.out_dir);
  std::vector<std::string> announced;
  options.on_scene = [&](const std::string& scene) { announced.push_back(scene); };
  const std::vector<dyn::ValidationRow> rows = dyn::run_validation(options);
  std::ostringstream table;
  dyn::write_validation_table(table, rows);
  BOOST_TEST_MESSAGE(table.str());

  std::set<std::string> sections;
  for (const dyn::ValidationRow& r : rows) {
    BOOST_TEST_CONTEXT(r.scene << ": " << r.check) {
      sections.insert(r.scene.substr(0, 3));
      BOOST_TEST(!r.check.empty());
      BOOST_TEST(!r.reference.empty());
      BOOST_TEST(!r.measured.empty());
      BOOST_TEST(r.seconds >= 0.0);
      BOOST_TEST(std::isfinite(r.error));  // no run was stopped
      const bool within =
          r.bound == dyn::Bound::at_most ? r.error <= r.tolerance : r.error >= r.tolerance;
      BOOST_TEST(r.pass == within);
    }
  }
  BOOST_TEST(sections ==
             (std::set<std::string>{"4.1", "4.2", "4.3", "5.1", "5.2", "5.3", "6.1", "6.2", "001", "003", "bar"}));
  // 3 (4.1) + 1 (4.2) + 3 x 2 (4.3) + 2 (5.1) + 2 (5.2) + 2 x 2 (5.3) + 2 (6.1 quick) + 1 (6.2 quick)
  // + 2 (seed 001 §6.1 wedge: factor of safety, frictionless slide) + 3 (seed 003 prisms: touch
  // time, momentum, velocity exchange) + 2 x 2 (bars, two-scale and penalty)
  BOOST_TEST(rows.size() == 30u);
  // 4.1, 4.2, three inclines, 5.1, 5.2, two 5.3, 6.1, 6.2, the wedge, the prisms, two bars
  BOOST_TEST(announced.size() == 15u);
  // One output directory per run: 4.1, 4.2, 3 inclines, 4 bounces, 5.2, 2 small-edge cases, two
  // collapses, the valley.
  std::size_t runs = 0;
  for (const auto& entry : fs::directory_iterator(options.out_dir)) {
    runs += fs::exists(entry.path() / "summary.json") ? 1 : 0;
  }
  BOOST_TEST(runs == 15u);
}
