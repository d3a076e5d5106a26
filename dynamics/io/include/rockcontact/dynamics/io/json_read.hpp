#pragma once
// Strict reading of JSON input documents (the pair files of `rockcontact pairs`, the scenes of
// `rockcontact run`): every field is checked, unknown fields are rejected, and every problem is
// an InputError reading "<source>: <path>: expected <what>, got <type> <value>", where <path> is
// the JSON path of the field ("blocks[1].vertices[2]", "materials.rock.density").
//
// A document is read in two steps: read_json_file turns a file into a JSON value (or an
// InputError carrying the parser's line and column), then a JsonReader bound to the source name
// checks the value field by field. The reader never converts silently: an integer field
// rejects 2.5, a number field rejects "2", and no field is defaulted behind the caller's back.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/equilibrium.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/material.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::dynamics {

// The path of member `key` of the object at `path` ("" is the document itself).
std::string json_child(const std::string& path, std::string_view key);

// The path of element `index` of the array at `path`.
std::string json_element(const std::string& path, std::size_t index);

// "<type> <value>" for messages ("string \"2\"", "number 1.5", "null"), cut short when long.
std::string describe_json(const nlohmann::json& value);

// Reads and parses a file. Throws InputError(file, "", ...) when the file cannot be opened or
// is not well-formed JSON (the message keeps the parser's line and column).
nlohmann::json read_json_file(const std::filesystem::path& file);

// One field of an object: its name, whether it must be present, and what it must hold (the
// "expected ..." of every message about it).
struct JsonField {
  std::string_view name;
  bool required;
  std::string_view expected;
};

// The entry of `fields` called `name`; it must be there (a programmer error otherwise).
const JsonField& json_field(std::span<const JsonField> fields, std::string_view name);

// Checks values of one document; knows its source name for every message.
class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  const std::string& source() const noexcept { return source_; }

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const;
  [[noreturn]] void fail_expected(const std::string& path, std::string_view expected,
                                  const nlohmann::json& got) const;

  // `value` must be an object whose members are all among `fields`, the required ones present.
  void check_object(const nlohmann::json& value, const std::string& path, std::string_view expected,
                    std::span<const JsonField> fields) const;

  double number(const nlohmann::json& value, const std::string& path,
                std::string_view expected) const;  // any finite number
  double positive(const nlohmann::json& value, const std::string& path,
                  std::string_view expected) const;  // finite, > 0
  double non_negative(const nlohmann::json& value, const std::string& path,
                      std::string_view expected) const;  // finite, >= 0
  std::int64_t integer(const nlohmann::json& value, const std::string& path,
                       std::string_view expected) const;  // a JSON integer (no fraction)
  bool boolean(const nlohmann::json& value, const std::string& path,
               std::string_view expected) const;
  // Every engine's "initial_equilibrium": true (strict), false (off) or "auto".
  InitialEquilibrium initial_equilibrium(const nlohmann::json& value, const std::string& path,
                                         std::string_view expected) const;
  const std::string& string(const nlohmann::json& value, const std::string& path,
                            std::string_view expected) const;

  // An array of exactly `count` finite numbers.
  std::vector<double> numbers(const nlohmann::json& value, const std::string& path,
                              std::size_t count, std::string_view expected) const;

  // An array of [x, y] vertices (each element checked; the polygon itself is not validated).
  std::vector<kernel::Point2> polygon(const nlohmann::json& value, const std::string& path,
                                      std::string_view expected) const;
  // An object {"vertices": [[x, y, z], ...], "faces": [[i, j, k, ...], ...]} with vertex
  // indices that are non-negative integers (each element checked; the polyhedron itself, index
  // ranges included, is validated by kernel::ConvexPolyhedron::make).
  PolyhedronSpec polyhedron(const nlohmann::json& value, const std::string& path,
                            std::string_view expected) const;

  // A string that `parse` accepts (one of a fixed set of names).
  template <class Choice>
  Choice choice(const nlohmann::json& value, const std::string& path, std::string_view expected,
                std::optional<Choice> (*parse)(std::string_view)) const {
    if (value.is_string()) {
      if (const auto parsed = parse(value.get_ref<const std::string&>())) return *parsed;
    }
    fail_expected(path, expected, value);
  }

 private:
  std::string source_;
};

// The "id" members of an array's elements, checked for repeats as the elements are read.
class UniqueIds {
 public:
  // Fails at "<array_path>[index].id" when `id` was seen before, naming the element that had it.
  void add(const JsonReader& reader, const std::string& array_path, std::size_t index,
           const std::string& id);

 private:
  std::unordered_map<std::string, std::size_t> first_index_;
};

// The material at `path` ("materials.<name>"): {"density", "youngs_modulus", "poisson_ratio"},
// the same in 2D and 3D scenes.
Material read_material(const JsonReader& reader, const nlohmann::json& value, const std::string& path);

// The time step and duration of a scene's "time" member, the same in every scene format.
struct SceneTime {
  double dt = 0.0;        // s
  double duration = 0.0;  // s
};

// Reads the "time" member `value`, an object of `fields` (which hold "dt" and "duration", and
// may hold more for the caller to read): dt and duration finite and > 0, duration / dt at most
// 1e12 steps (a run of more would take weeks, and its step count must fit a size_t). Fails at
// "time", "time.dt" or "time.duration".
SceneTime read_scene_time(const JsonReader& reader, const nlohmann::json& value,
                          std::string_view expected, std::span<const JsonField> fields);

// The material a block names: the string `value` at `path`, looked up in `materials`; fails at
// `path` for another type or an unknown name, listing the names there are.
template <class Material>
const Material& find_material(const JsonReader& reader, const nlohmann::json& value,
                              const std::string& path, std::string_view expected,
                              const std::map<std::string, Material, std::less<>>& materials) {
  const std::string& name = reader.string(value, path, expected);
  const auto it = materials.find(name);
  if (it == materials.end()) {
    std::string names;
    for (const auto& [known, m] : materials) names += (names.empty() ? "" : ", ") + known;
    reader.fail(path, "unknown material \"" + name + "\"; expected one of the scene's " +
                          "materials (" + (names.empty() ? "none defined" : names) + ")");
  }
  return it->second;
}

// The "output" member of a scene, the same in every scene format.
struct SceneOutput {
  std::vector<std::string> track;  // ids of the tracked blocks, in the file's order
  std::size_t every = 100;         // record every `every` steps
};

// Reads document["output"] (optional): {"track": [block ids], "every": steps >= 1 (default
// 100)}. `ids` are the scene's block ids; without "track", the blocks of `default_track` are
// tracked (every block that is not fixed). Fails at "output.every" or at "output.track[i]" for
// an id no block has or one listed twice.
SceneOutput read_scene_output(const JsonReader& reader, const nlohmann::json& document,
                              std::span<const std::string> ids,
                              std::vector<std::string> default_track);

// The same for a scene's block specifications (2D, 3D or CDEM: each with an `id` and `fixed`).
template <class BlockSpecs>
SceneOutput read_scene_output(const JsonReader& reader, const nlohmann::json& document,
                              const BlockSpecs& blocks) {
  std::vector<std::string> ids, movable;
  for (const auto& b : blocks) {
    ids.push_back(b.id);
    if (!b.fixed) movable.push_back(b.id);
  }
  return read_scene_output(reader, document, ids, std::move(movable));
}

}  // namespace rockcontact::dynamics
