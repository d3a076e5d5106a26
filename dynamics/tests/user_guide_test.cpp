#define BOOST_TEST_MODULE user_guide
// The JSON examples of docs/user-guide.md and of the README load as they are printed.
//
// Every fenced ```json block is parsed with nlohmann::json. A block with "solver": "cdem" is a
// CDEM scene and goes through parse_scene_cdem (checked first, as `rockcontact run` does: its
// "dimension" is optional); another block with "dimension" is a scene and goes through
// parse_scene (parse_scene3d for "dimension": 3); a block with "pairs" is a `rockcontact pairs`
// input and goes through parse_pairs; any other block (an excerpt of an output file) must at
// least be JSON.
// A block preceded by the line <!-- invalid --> is an example of a mistake: it must throw
// InputError (malformed JSON counts too). The guide's first scene, its first 3D scene and its
// first CDEM scene are also run to their end, and what the guide says they write must be there.

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/dynamics/io/scene3d_output.hpp"
#include "rockcontact/dynamics/io/scene_cdem.hpp"
#include "rockcontact/dynamics/io/scene_cdem_output.hpp"
#include "rockcontact/dynamics/io/scene_output.hpp"

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Block {
  std::size_t number = 0;  // 1-based, in the order of the file's ```json fences
  std::size_t line = 0;    // of the opening fence, 1-based
  bool invalid = false;    // preceded by <!-- invalid -->
  std::string text;
};

std::string trimmed(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const std::size_t last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// The ```json blocks of a markdown file. The marker may be separated from its fence by blank
// lines only.
std::vector<Block> json_blocks(const fs::path& file) {
  std::ifstream in(file);
  BOOST_TEST_REQUIRE(in.good(), "cannot open " << file);
  std::vector<Block> blocks;
  std::string line, last_text;
  std::size_t number = 0;
  bool inside = false, fenced_other = false;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    const std::string t = trimmed(line);
    if (inside) {
      if (t == "```") {
        inside = false;
        last_text.clear();
      } else {
        blocks.back().text += line + '\n';
      }
      continue;
    }
    if (fenced_other) {  // inside a fence of another language: its lines are not markdown
      if (t == "```") fenced_other = false;
      continue;
    }
    if (t == "```json") {
      inside = true;
      blocks.push_back({++number, n, last_text == "<!-- invalid -->", ""});
    } else if (t.rfind("```", 0) == 0) {
      fenced_other = true;
      last_text.clear();
    } else if (!t.empty()) {
      last_text = t;
    }
  }
  BOOST_TEST(!inside, file << " ends inside a ```json block");
  return blocks;
}

std::string name_of(const fs::path& file, const Block& b) {
  return file.filename().string() + " block " + std::to_string(b.number) + " (line " +
         std::to_string(b.line) + ")";
}

enum class Kind { scene, scene_cdem, pairs, other };

Kind kind_of(const json& doc) {
  if (dyn::is_scene_cdem_document(doc)) return Kind::scene_cdem;
  if (doc.is_object() && doc.contains("pairs")) return Kind::pairs;
  if (doc.is_object() && doc.contains("dimension")) return Kind::scene;
  return Kind::other;
}

// Parses the block as what it is; throws what the reader throws.
Kind load(const Block& b, const std::string& name) {
  json doc;
  try {
    doc = json::parse(b.text);
  } catch (const json::parse_error& e) {
    throw dyn::InputError(name, "", std::string("malformed JSON: ") + e.what());
  }
  const Kind kind = kind_of(doc);
  if (kind == Kind::scene_cdem) dyn::parse_scene_cdem(doc, name);
  if (kind == Kind::scene && dyn::is_scene3d_document(doc)) {
    dyn::parse_scene3d(doc, name);
  } else if (kind == Kind::scene) {
    dyn::parse_scene(doc, name);
  }
  if (kind == Kind::pairs) dyn::parse_pairs(doc, name);
  return kind;
}

struct Counts {
  std::size_t scenes = 0, scenes3d = 0, scenes_cdem = 0, pairs = 0, invalid = 0;
};

Counts check_file(const fs::path& file) {
  Counts counts;
  for (const Block& b : json_blocks(file)) {
    const std::string name = name_of(file, b);
    BOOST_TEST_CONTEXT(name) {
      if (b.invalid) {
        ++counts.invalid;
        BOOST_CHECK_THROW(load(b, name), dyn::InputError);
        continue;
      }
      try {
        const Kind kind = load(b, name);
        counts.scenes += kind == Kind::scene;
        counts.scenes3d += kind == Kind::scene && dyn::is_scene3d_document(json::parse(b.text));
        counts.scenes_cdem += kind == Kind::scene_cdem;
        counts.pairs += kind == Kind::pairs;
      } catch (const std::exception& e) {
        BOOST_ERROR(name << " does not load: " << e.what());
      }
    }
  }
  return counts;
}

const fs::path guide = ROCKCONTACT_USER_GUIDE;
const fs::path readme = ROCKCONTACT_README;

}  // namespace

BOOST_AUTO_TEST_CASE(every_json_block_of_the_guide_loads_or_fails_as_marked) {
  const Counts counts = check_file(guide);
  // The guide shows scenes, a pairs input and mistakes; finding none means the extraction broke.
  BOOST_TEST(counts.scenes >= 3u);
  BOOST_TEST(counts.scenes3d >= 1u);
  BOOST_TEST(counts.scenes_cdem >= 1u);
  BOOST_TEST(counts.pairs >= 1u);
  BOOST_TEST(counts.invalid >= 1u);
}

BOOST_AUTO_TEST_CASE(the_readme_scene_loads) {
  const Counts counts = check_file(readme);
  BOOST_TEST(counts.scenes >= 1u);
}

// The README's scene is the guide's first scene: one example, shown twice.
BOOST_AUTO_TEST_CASE(the_readme_scene_is_the_first_scene_of_the_guide) {
  auto first_scene = [](const fs::path& file) {
    for (const Block& b : json_blocks(file)) {
      if (b.invalid) continue;
      const json doc = json::parse(b.text, nullptr, false);
      if (!doc.is_discarded() && kind_of(doc) == Kind::scene) return doc;
    }
    return json();
  };
  const json from_guide = first_scene(guide);
  BOOST_TEST_REQUIRE(!from_guide.is_null());
  BOOST_TEST(from_guide == first_scene(readme));
}

// The first scene, run to its end as `rockcontact run my_scene.json --out out` runs it.
BOOST_AUTO_TEST_CASE(the_first_scene_runs_and_writes_what_the_guide_lists) {
  const std::vector<Block> blocks = json_blocks(guide);
  const Block* first = nullptr;
  for (const Block& b : blocks) {
    const json doc = json::parse(b.text, nullptr, false);
    if (!b.invalid && !doc.is_discarded() && kind_of(doc) == Kind::scene) {
      first = &b;
      break;
    }
  }
  BOOST_TEST_REQUIRE(first != nullptr);
  const dyn::Scene scene = dyn::parse_scene(json::parse(first->text), "my_scene.json");
  const fs::path dir = fs::current_path() / "user_guide_test" / "first_scene";
  fs::remove_all(dir);
  dyn::RunOptions options;
  options.out_dir = dir;
  const dyn::RunReport report = dyn::run_scene(scene, options);
  BOOST_TEST(report.status == "completed", report.error);
  BOOST_TEST(report.steps == dyn::step_count(scene));
  for (const char* file : {"tracks.csv", "energies.csv", "contacts.csv", "contacts.pvd", "summary.json",
                           "frames.pvd", "final.svg"}) {
    BOOST_TEST(fs::exists(dir / file), file);
  }
  BOOST_TEST(report.frames >= 2u);
  std::ifstream in(dir / "summary.json");
  const json summary = json::parse(in);
  BOOST_TEST(summary.at("status").get<std::string>() == "completed");
  BOOST_TEST(summary.at("steps").get<std::size_t>() == report.steps);
}

// The guide's first 3D scene, run to its end: the files its "What a 3D run writes" lists.
BOOST_AUTO_TEST_CASE(the_first_3d_scene_runs_and_writes_what_the_guide_lists) {
  json document;
  for (const Block& b : json_blocks(guide)) {
    const json doc = json::parse(b.text, nullptr, false);
    if (!b.invalid && !doc.is_discarded() && kind_of(doc) == Kind::scene &&
        dyn::is_scene3d_document(doc)) {
      document = doc;
      break;
    }
  }
  BOOST_TEST_REQUIRE(!document.is_null());
  const dyn::Scene3d scene = dyn::parse_scene3d(document, "my_scene3d.json");
  const fs::path dir = fs::current_path() / "user_guide_test" / "first_scene3d";
  fs::remove_all(dir);
  dyn::Run3dOptions options;
  options.out_dir = dir;
  const dyn::Run3dReport report = dyn::run_scene3d(scene, options);
  BOOST_TEST(report.status == "completed", report.error);
  BOOST_TEST(report.time >= scene.duration * (1.0 - 1e-12));
  for (const char* file :
       {"tracks.csv", "contacts.csv", "frames.pvd", "final.svg", "summary.json"}) {
    BOOST_TEST(fs::exists(dir / file), file);
  }
  BOOST_TEST(report.frames >= 2u);
}

// The guide's first CDEM scene, run to its end: the files its "What a CDEM run writes" lists, and
// the first touch it states (the rock's free fall of 0.05 m, sqrt(2 * 0.05 / 9.81) s, to 1e-9 s:
// velocity Verlet puts the nodes exactly on the free-fall parabola at every step, and the touch
// is exact for their straight path inside the step, the parabola's chord, at most
// g dt² / 8 = 1.2e-10 m from it: about 1.2e-10 s at the landing speed of 0.99 m/s).
BOOST_AUTO_TEST_CASE(the_first_cdem_scene_runs_and_writes_what_the_guide_lists) {
  json document;
  for (const Block& b : json_blocks(guide)) {
    const json doc = json::parse(b.text, nullptr, false);
    if (!b.invalid && !doc.is_discarded() && kind_of(doc) == Kind::scene_cdem) {
      document = doc;
      break;
    }
  }
  BOOST_TEST_REQUIRE(!document.is_null());
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(document, "my_cdem.json");
  const fs::path dir = fs::current_path() / "user_guide_test" / "first_scene_cdem";
  fs::remove_all(dir);
  dyn::RunCdemOptions options;
  options.out_dir = dir;
  const dyn::RunCdemReport report = dyn::run_scene_cdem(scene, options);
  BOOST_TEST(report.status == "completed", report.error);
  BOOST_TEST(report.steps == dyn::step_count(scene));
  for (const char* file : {"tracks.csv", "events.csv", "frames.pvd", "final.svg", "summary.json"}) {
    BOOST_TEST(fs::exists(dir / file), file);
  }
  BOOST_TEST(report.frames >= 2u);
  std::ifstream events(dir / "events.csv");
  std::string header, first;
  std::getline(events, header);
  std::getline(events, first);
  BOOST_TEST(header == "t,event,block_a,block_b");
  BOOST_TEST(first.find(",touch,rock,floor") != std::string::npos, first);
  const double touch = std::stod(first.substr(0, first.find(',')));
  BOOST_TEST(std::abs(touch - std::sqrt(2.0 * 0.05 / 9.81)) <= 1e-9, "first touch at " << touch);
  std::ifstream tracks(dir / "tracks.csv");
  std::getline(tracks, header);
  BOOST_TEST(header == "t,block,x,y,rotation,vx,vy,omega");
  std::ifstream in(dir / "summary.json");
  const json summary = json::parse(in);
  BOOST_TEST(summary.at("solver").get<std::string>() == "cdem");
  BOOST_TEST(summary.at("status").get<std::string>() == "completed");
  // The mesh and the critical step the guide quotes (the mesher's numbering and refinement depend
  // only on the geometry).
  BOOST_TEST(report.elements == 164u);
  BOOST_TEST(report.nodes == 118u);
  BOOST_TEST(std::abs(summary.at("critical_dt").get<double>() / 1.58e-5 - 1.0) <= 0.005);
}
