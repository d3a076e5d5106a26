#define BOOST_TEST_MODULE robustness_bad_input_json
#include <boost/test/unit_test.hpp>

// Both JSON formats (scene files and `pairs` inputs) against systematic corruption: every field
// of a document that uses every feature of its format is corrupted in turn, and the reader must
// answer with an InputError whose path names that field (or the element holding it), never with
// another exception, a crash or a silently different document. Then the semantic errors the
// formats document (scene.hpp, pairs_io.hpp) one by one, each with the path and the words the
// message must carry.
//
// Corruptions, applied to every field reached by walking the document:
//   * wrong type: a number becomes a string, a string and a bool become the other kind, an
//     array or object becomes a number. Every field of both formats has one JSON type or a
//     fixed set of string values, so each of these must be rejected at that field's path.
//   * unknown member: "bogus_field" added to every object must be named in the error.
//   * removal: each member removed in turn. The format documents which members are optional;
//     the members whose removal the reader accepts must be exactly those (the lists below are
//     copied from the documentation, not from the reader), and for the others the error must
//     name the missing member.
//   * extreme numbers: every number set to -1, 0, 1e-300, 1e300 and -1e300. The reader may
//     accept a value the format allows; then the engine (Dda2d) must accept it or refuse it
//     with its documented errors (std::invalid_argument naming the block or parameter, or
//     StabilityError for the time step). Nothing else may escape, and nothing may hang: the
//     block cutting bounds its work (kernel/block_cutting.hpp).

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/io/scene.hpp"

namespace {

namespace dyn = rockcontact::dynamics;
using nlohmann::json;

// A scene using every field of the format: explicit convex and non-convex blocks, a region cut
// by a persistent and a non-persistent joint set, an interface, a boundary segment, friction and output options.
// Blocks touch but do not overlap, and dt is below the critical estimate, so the engine accepts
// it as it is (checked below).
const json full_scene = json::parse(R"({
  "description": "every field of the scene format",
  "dimension": 2,
  "time": {"dt": 1e-5, "duration": 0.01},
  "gravity": [0, -9.81],
  "plane": "strain",
  "damping": 0.5,
  "initial_equilibrium": true,
  "materials": {"rock": {"density": 2600, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
  "contact": {"law": "potential", "kn": 1e8, "H": "mean_edge", "kt": 1e7,
              "friction_angle_deg": 30, "friction": "elastoplastic", "cohesion": 1e4,
              "damping_ratio": 0.05, "policy": "filtered", "demarcation": "exact"},
  "blocks": [
    {"id": "base", "material": "rock", "vertices": [[0, 0], [10, 0], [10, 1], [0, 1]],
     "fixed": true, "group": "floor"},
    {"id": "ell", "material": "rock", "vertices": [[1, 1], [3, 1], [3, 2], [2, 2], [2, 3], [1, 3]],
     "group": "rock", "rigid": false, "velocity": [0.1, 0, 0]}],
  "region": {"vertices": [[5, 1], [8, 1], [8, 4], [5, 4]], "material": "rock", "group": "rock",
             "id_prefix": "cut", "min_block_area": 0.01},
  "joint_sets": [{"dip_deg": 90, "spacing": 1.0, "offset": 0.5},
                 {"dip_deg": 30, "spacing": 1.0, "offset": 0.1, "length": 2.0, "gap": 0.5}],
  "interfaces": [{"between": ["rock", "floor"], "kn": 2e8, "kt": 2e7, "friction_angle_deg": 20,
                  "cohesion": 5e3}],
  "boundaries": [{"id": "wall", "material": "rock", "from": [0, 5], "to": [0, 1], "depth": 1.0,
                  "group": "floor"}],
  "output": {"track": ["ell"], "every": 10}
})");

// The members scene.hpp calls optional (with a default), by path. "blocks" is optional when a
// region is given, but "output.track" names the block "ell", so not here; "region" is optional
// when blocks are given, but not while joint sets are ("joint_sets": with "region"). kt and
// friction_angle_deg go "both or neither", so neither alone is optional; "gap" is optional,
// "length" is not while a gap is given ("gap": with length).
const std::set<std::string> scene_optional = {
    "description",          "gravity",          "plane",
    "damping",              "contact.policy",   "contact.demarcation",
    "initial_equilibrium",  "contact.friction", "contact.cohesion", "contact.damping_ratio",
    "interfaces[0].cohesion",
    "blocks[0].group",  "blocks[0].fixed",
    "blocks[1].group",      "blocks[1].rigid",  "blocks[1].velocity",
    "region.group",         "region.id_prefix", "region.min_block_area",
    "joint_sets",           "joint_sets[0].offset", "joint_sets[1].offset",
    "joint_sets[1].gap",
    "interfaces",           "interfaces[0].kn", "interfaces[0].kt",
    "interfaces[0].friction_angle_deg",         "boundaries",
    "boundaries[0].depth",  "boundaries[0].group", "output",
    "output.track",         "output.every"};

const json full_pairs = json::parse(R"({
  "kn": 1e9, "H": 0.5, "policy": "exact", "demarcation": "paper",
  "pairs": [{"id": "p0", "cp": [[0, 0], [1, 0], [1, 1], [0, 1]],
             "tp": [[0.5, 0.5], [1.5, 0.5], [1.5, 1.5]]}]
})");

const std::set<std::string> pairs_optional = {"policy", "demarcation"};

// Every value in a document with its path in the readers' notation ("blocks[1].vertices[2]",
// "materials.rock.density") and its JSON pointer.
struct Field {
  std::string path;
  json::json_pointer pointer;
};

void collect(const json& value, const std::string& path, const json::json_pointer& pointer,
             std::vector<Field>& out) {
  if (!path.empty()) out.push_back({path, pointer});
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      collect(child, dyn::json_child(path, key), pointer / key, out);
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      collect(value[i], dyn::json_element(path, i), pointer / i, out);
    }
  }
}

std::vector<Field> fields_of(const json& document) {
  std::vector<Field> out;
  collect(document, "", json::json_pointer(), out);
  return out;
}

// True when `ancestor` is `path` or a path above it ("blocks[1]" is above "blocks[1].id" and
// "blocks[1].vertices[0]", not above "blocks[10]").
bool at_or_above(const std::string& ancestor, const std::string& path) {
  if (path.compare(0, ancestor.size(), ancestor) != 0) return false;
  return path.size() == ancestor.size() || path[ancestor.size()] == '.' ||
         path[ancestor.size()] == '[';
}

// Whether an error at `error_path` is about the corrupted field at `field_path`: at the field
// or above it, or at a field the format ties it to: another vertex of the same polygon (a
// repeated or collinear vertex is reported at the later one), or a joint set for a region's
// vertex (an outline too large for the spacing is the joint set's error: it names the count of
// traces the spacing would give).
bool names_the_field(const std::string& error_path, const std::string& field_path) {
  if (error_path.empty()) return false;
  if (at_or_above(error_path, field_path)) return true;
  const std::size_t vertices = field_path.find(".vertices[");
  if (vertices != std::string::npos &&
      at_or_above(field_path.substr(0, vertices + 9), error_path)) {
    return true;
  }
  return field_path.rfind("region", 0) == 0 && error_path.rfind("joint_sets[", 0) == 0;
}

// What a reader did with a document: nothing thrown, an InputError, or anything else (a bug).
struct Outcome {
  enum class Kind { accepted, input_error, other } kind = Kind::accepted;
  std::string path;     // InputError::path()
  std::string message;  // what()
};

Outcome outcome_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const dyn::InputError& e) {
    return {Outcome::Kind::input_error, e.path(), e.what()};
  } catch (const std::exception& e) {
    return {Outcome::Kind::other, "", e.what()};
  }
  return {};
}

const char* source = "corrupt.json";

Outcome read_scene(const json& document) {
  return outcome_of([&] { dyn::parse_scene(document, source); });
}

Outcome read_pairs(const json& document) {
  return outcome_of([&] { dyn::parse_pairs(document, source); });
}

// A value of another JSON type than `value`'s, of a kind no field of either format accepts in
// its place.
json wrong_type(const json& value) {
  if (value.is_number()) return "text";
  if (value.is_string()) return true;
  if (value.is_boolean()) return "yes";
  return 17;  // an array or an object
}

void check_wrong_types(const json& document, const std::function<Outcome(const json&)>& read) {
  for (const Field& field : fields_of(document)) {
    json corrupt = document;
    corrupt[field.pointer] = wrong_type(document[field.pointer]);
    const Outcome outcome = read(corrupt);
    BOOST_TEST_CONTEXT(field.path << " = " << corrupt[field.pointer].dump()) {
      BOOST_TEST_REQUIRE((outcome.kind == Outcome::Kind::input_error), outcome.message);
      // The error is at the field or at the vertex / element holding it ("blocks[1].vertices[2]"
      // for a corrupt coordinate), never at the document as a whole.
      BOOST_TEST(!outcome.path.empty(), outcome.message);
      BOOST_TEST(at_or_above(outcome.path, field.path), outcome.message);
      BOOST_TEST(outcome.message.find(std::string(source) + ": " + outcome.path + ": ") == 0u,
                 outcome.message);
    }
  }
}

void check_unknown_members(const json& document, const std::function<Outcome(const json&)>& read) {
  std::vector<Field> objects = fields_of(document);
  objects.insert(objects.begin(), Field{"", json::json_pointer()});
  for (const Field& field : objects) {
    if (!document[field.pointer].is_object()) continue;
    json corrupt = document;
    corrupt[field.pointer]["bogus_field"] = 1;
    const Outcome outcome = read(corrupt);
    BOOST_TEST_CONTEXT("bogus_field in " << (field.path.empty() ? "the document" : field.path)) {
      BOOST_TEST_REQUIRE((outcome.kind == Outcome::Kind::input_error), outcome.message);
      BOOST_TEST(outcome.path == dyn::json_child(field.path, "bogus_field"), outcome.message);
    }
  }
}

// Removals whose error is reported where the missing member is referred to.
using KnockOns = std::set<std::pair<std::string, std::string>>;  // {removed, error path}

void check_removals(const json& document, const std::function<Outcome(const json&)>& read,
                    const std::set<std::string>& documented_optional, const KnockOns& knock_ons) {
  std::set<std::string> accepted;
  for (const Field& field : fields_of(document)) {
    if (!document[field.pointer.parent_pointer()].is_object()) continue;
    json corrupt = document;
    corrupt[field.pointer.parent_pointer()].erase(field.pointer.back());
    const Outcome outcome = read(corrupt);
    BOOST_TEST_CONTEXT("without " << field.path) {
      BOOST_TEST((outcome.kind != Outcome::Kind::other), outcome.message);
      if (outcome.kind == Outcome::Kind::accepted) {
        accepted.insert(field.path);
      } else if (outcome.kind == Outcome::Kind::input_error &&
                 !knock_ons.contains({field.path, outcome.path})) {
        BOOST_TEST(outcome.message.find(field.pointer.back()) != std::string::npos,
                   outcome.message);
      }
    }
  }
  BOOST_TEST(accepted == documented_optional, boost::test_tools::per_element());
}

// The engine's documented refusals; anything else escaping it is a bug.
void check_engine_accepts_or_refuses(const dyn::Scene& scene, const std::string& what) {
  try {
    dyn::Dda2d engine(scene.blocks, scene.law, scene.params);
  } catch (const dyn::StabilityError&) {
  } catch (const std::invalid_argument&) {  // also kernel::InvalidPolygon, InvalidCut
  } catch (const std::exception& e) {
    BOOST_ERROR(what << ": the engine threw an undocumented exception: " << e.what());
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(the_full_documents_are_valid) {
  const dyn::Scene scene = dyn::parse_scene(full_scene, source);
  BOOST_TEST(scene.blocks.size() > 4u);  // base, ell, the region's blocks, the wall
  BOOST_TEST(scene.generated_count > 1u);
  BOOST_CHECK_NO_THROW(dyn::Dda2d(scene.blocks, scene.law, scene.params));
  const dyn::PairsInput pairs = dyn::parse_pairs(full_pairs, source);
  BOOST_TEST(pairs.pairs.size() == 1u);
}

BOOST_AUTO_TEST_CASE(scene_every_field_of_the_wrong_type) { check_wrong_types(full_scene, read_scene); }
BOOST_AUTO_TEST_CASE(pairs_every_field_of_the_wrong_type) { check_wrong_types(full_pairs, read_pairs); }

BOOST_AUTO_TEST_CASE(scene_unknown_member_in_every_object) {
  check_unknown_members(full_scene, read_scene);
}
BOOST_AUTO_TEST_CASE(pairs_unknown_member_in_every_object) {
  check_unknown_members(full_pairs, read_pairs);
}

BOOST_AUTO_TEST_CASE(scene_removal_of_every_member) {
  // Without "blocks", the tracked block "ell" is unknown.
  check_removals(full_scene, read_scene, scene_optional,
                 {{"blocks", "output.track[0]"}});
}
BOOST_AUTO_TEST_CASE(pairs_removal_of_every_member) {
  check_removals(full_pairs, read_pairs, pairs_optional, {});
}

BOOST_AUTO_TEST_CASE(scene_extreme_numbers_reach_no_undocumented_failure) {
  for (const Field& field : fields_of(full_scene)) {
    if (!full_scene[field.pointer].is_number()) continue;
    for (const double value : {-1.0, 0.0, 1e-300, 1e300, -1e300}) {
      json corrupt = full_scene;
      corrupt[field.pointer] = value;
      BOOST_TEST_CONTEXT(field.path << " = " << value) {
        std::optional<dyn::Scene> scene;
        const Outcome outcome = outcome_of([&] { scene = dyn::parse_scene(corrupt, source); });
        BOOST_TEST((outcome.kind != Outcome::Kind::other), outcome.message);
        if (outcome.kind == Outcome::Kind::input_error) {
          BOOST_TEST(names_the_field(outcome.path, field.path), outcome.message);
        }
        if (scene) check_engine_accepts_or_refuses(*scene, field.path);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(pairs_extreme_numbers_are_read_or_refused_and_evaluated) {
  for (const Field& field : fields_of(full_pairs)) {
    if (!full_pairs[field.pointer].is_number()) continue;
    for (const double value : {-1.0, 0.0, 1e-300, 1e300, -1e300}) {
      json corrupt = full_pairs;
      corrupt[field.pointer] = value;
      BOOST_TEST_CONTEXT(field.path << " = " << value) {
        std::optional<dyn::PairsInput> input;
        const Outcome outcome = outcome_of([&] { input = dyn::parse_pairs(corrupt, source); });
        BOOST_TEST((outcome.kind != Outcome::Kind::other), outcome.message);
        if (!input) continue;
        // A read document is evaluated; a polygon the kernel refuses is that pair's "error"
        // result, and every other result is a status with finite numbers.
        const auto results = dyn::run_pairs(*input).at("results");
        for (const auto& result : results) {
          const std::string status = result.at("status");
          BOOST_TEST((status == "error" || status == "separate" || status == "touch" ||
                      status == "overlap"),
                     status);
          if (status == "overlap") {
            BOOST_TEST(result.at("force").at(0).is_number_float());
            BOOST_TEST(result.at("force").at(1).is_number_float());
          }
        }
      }
    }
  }
}

// The semantic errors the scene format documents, each with the path and words of its message.
BOOST_AUTO_TEST_CASE(scene_documented_semantic_errors) {
  struct Case {
    std::string pointer;
    json value;
    std::string path;
    std::string words;
  };
  const std::vector<Case> cases = {
      {"/time/dt", 0.0, "time.dt", "> 0"},
      {"/time/dt", -1e-3, "time.dt", "> 0"},
      {"/time/duration", 0.0, "time.duration", "> 0"},
      {"/time/duration", 1e300, "time", "at most 1e12 steps"},
      {"/materials/rock/density", -2600.0, "materials.rock.density", "> 0"},
      {"/materials/rock/poisson_ratio", 0.5, "materials.rock.poisson_ratio", "0.5"},
      {"/joint_sets/0/spacing", -1.0, "joint_sets[0].spacing", "> 0"},
      {"/joint_sets/0/dip_deg", 180.0, "joint_sets[0].dip_deg", "180"},
      {"/contact/friction_angle_deg", 90.0, "contact.friction_angle_deg", "90"},
      {"/contact/friction", "coulomb", "contact.friction", "elastoplastic"},
      {"/contact/cohesion", -1.0, "contact.cohesion", ">= 0"},
      {"/contact/damping_ratio", -0.1, "contact.damping_ratio", ">= 0"},
      {"/interfaces/0/cohesion", -1.0, "interfaces[0].cohesion", ">= 0"},
      {"/contact/H", "largest", "contact.H", "mean_edge"},
      {"/output/every", 0, "output.every", ">= 1"},
      {"/output/every", 2.5, "output.every", "integer"},
      // Clockwise, repeated, collinear (zero area) and self-intersecting outlines.
      {"/blocks/1/vertices", json::parse("[[1,1],[1,3],[2,3],[2,2],[3,2],[3,1]]"),
       "blocks[1].vertices", "clockwise"},
      {"/blocks/1/vertices", json::parse("[[1,1],[3,1],[3,1],[1,3]]"), "blocks[1].vertices[2]",
       "repeat"},
      {"/blocks/1/vertices", json::parse("[[1,1],[2,1],[3,1]]"), "blocks[1].vertices", "collinear"},
      {"/blocks/1/vertices", json::parse("[[1,1],[3,1],[1,3],[3,3]]"), "blocks[1].vertices",
       "simple"},
      {"/blocks/1/material", "granite", "blocks[1].material", "materials"},
      {"/blocks/0/velocity", json::parse("[1, 0, 0]"), "blocks[0]", "fixed"},
      {"/region/vertices", json::parse("[[5,1],[5,4],[8,4],[8,1]]"), "region.vertices",
       "clockwise"},
      {"/joint_sets/1/length", 0.0, "joint_sets[1].length", "> 0"},
      {"/interfaces/0/between", json::parse(R"(["rock", "magma"])"), "interfaces[0].between[1]",
       "magma"},
      {"/output/track", json::parse(R"(["nobody"])"), "output.track[0]", "nobody"},
      {"/boundaries/0/to", json::parse("[0, 5]"), "boundaries[0].to", "distinct"},
  };
  for (const Case& c : cases) {
    json corrupt = full_scene;
    corrupt[json::json_pointer(c.pointer)] = c.value;
    const Outcome outcome = read_scene(corrupt);
    BOOST_TEST_CONTEXT(c.pointer << " = " << c.value.dump()) {
      BOOST_TEST_REQUIRE((outcome.kind == Outcome::Kind::input_error), outcome.message);
      BOOST_TEST(at_or_above(c.path, outcome.path), outcome.message);
      BOOST_TEST(outcome.message.find(c.words) != std::string::npos, outcome.message);
    }
  }
}

// A pair whose polygon the kernel refuses is reported in its result, naming the polygon and
// the vertex, while the other pairs are computed (pairs_io.hpp); the document-level errors are
// InputErrors at their path.
BOOST_AUTO_TEST_CASE(pairs_documented_semantic_errors) {
  struct PolygonCase {
    json cp;
    std::string words;
  };
  const std::vector<PolygonCase> polygons = {
      {json::parse("[[0,0],[0,1],[1,1],[1,0]]"), "clockwise"},
      {json::parse("[[0,0],[1,0],[1,0],[0,1]]"), "repeat"},
      {json::parse("[[0,0],[1,0],[2,0]]"), "collinear"},
      {json::parse("[[0,0],[2,0],[1,0.2],[1,2]]"), "convex"},
  };
  for (const PolygonCase& c : polygons) {
    json document = full_pairs;
    document["pairs"].push_back(document["pairs"][0]);
    document["pairs"][1]["id"] = "bad";
    document["pairs"][1]["cp"] = c.cp;
    const auto results = dyn::run_pairs(dyn::parse_pairs(document, source)).at("results");
    BOOST_TEST_CONTEXT(c.cp.dump()) {
      BOOST_TEST(results.at(0).at("status") == "overlap");
      BOOST_TEST(results.at(1).at("status") == "error");
      const std::string message = results.at(1).at("error");
      BOOST_TEST(message.find("pairs[1].cp") != std::string::npos, message);
      BOOST_TEST(message.find(c.words) != std::string::npos, message);
    }
  }
  struct DocumentCase {
    std::string pointer;
    json value;
    std::string path;
  };
  const std::vector<DocumentCase> documents = {
      {"/kn", 0.0, "kn"},
      {"/H", -0.5, "H"},
      {"/policy", "fast", "policy"},
      {"/demarcation", "approximate", "demarcation"},
      {"/pairs/0/cp/1", json::parse("[1]"), "pairs[0].cp[1]"},
      {"/pairs/0/cp/1", json::parse("[1, 2, 3]"), "pairs[0].cp[1]"},
  };
  for (const DocumentCase& c : documents) {
    json corrupt = full_pairs;
    corrupt[json::json_pointer(c.pointer)] = c.value;
    const Outcome outcome = read_pairs(corrupt);
    BOOST_TEST_CONTEXT(c.pointer << " = " << c.value.dump()) {
      BOOST_TEST_REQUIRE((outcome.kind == Outcome::Kind::input_error), outcome.message);
      BOOST_TEST(outcome.path == c.path, outcome.message);
    }
  }
}
