#include "rockcontact/dynamics/io/json_read.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace rockcontact::dynamics {

using nlohmann::json;

std::string json_child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string json_element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string describe_json(const json& value) {
  constexpr std::size_t max_shown = 40;
  if (value.is_null()) return "null";
  // A document built in memory may hold NaN or infinity, which dump() would print as null.
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    return "non-finite number " + std::to_string(value.get<double>());
  }
  std::string text = value.dump();
  if (text.size() > max_shown) text = text.substr(0, max_shown) + "...";
  return std::string(value.type_name()) + " " + text;
}

json read_json_file(const std::filesystem::path& file) {
  const std::string source = file.string();
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(source, "", "cannot open the file for reading");
  try {
    return json::parse(stream);
  } catch (const json::exception& e) {
    // nlohmann's messages start with "[json.exception.<kind>.<id>] "; the rest carries the
    // line and column of a syntax error.
    const std::string_view what = e.what();
    const auto end_of_tag = what.find("] ");
    const auto detail = end_of_tag == std::string_view::npos ? what : what.substr(end_of_tag + 2);
    throw InputError(source, "", "malformed JSON: " + std::string(detail));
  }
}

const JsonField& json_field(std::span<const JsonField> fields, std::string_view name) {
  return *std::find_if(fields.begin(), fields.end(),
                       [&](const JsonField& f) { return f.name == name; });
}

void JsonReader::fail(const std::string& path, const std::string& problem) const {
  throw InputError(source_, path, problem);
}

void JsonReader::fail_expected(const std::string& path, std::string_view expected,
                               const json& got) const {
  fail(path, "expected " + std::string(expected) + ", got " + describe_json(got));
}

void JsonReader::check_object(const json& value, const std::string& path, std::string_view expected,
                              std::span<const JsonField> fields) const {
  if (!value.is_object()) fail_expected(path, expected, value);
  std::string names;
  for (const JsonField& f : fields) names += (names.empty() ? "" : ", ") + std::string(f.name);
  for (const auto& member : value.items()) {
    // A reference, not a structured binding: clang 14 cannot capture a binding in a lambda.
    const std::string& key = member.key();
    const bool known = std::any_of(fields.begin(), fields.end(),
                                   [&](const JsonField& f) { return f.name == key; });
    if (!known) fail(json_child(path, key), "unknown field; expected only " + names);
  }
  for (const JsonField& f : fields) {
    if (f.required && !value.contains(f.name)) {
      fail(json_child(path, f.name), "missing field; expected " + std::string(f.expected));
    }
  }
}

double JsonReader::number(const json& value, const std::string& path,
                          std::string_view expected) const {
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    fail_expected(path, expected, value);
  }
  return value.get<double>();
}

double JsonReader::positive(const json& value, const std::string& path,
                            std::string_view expected) const {
  if (!value.is_number() || !std::isfinite(value.get<double>()) || !(value.get<double>() > 0.0)) {
    fail_expected(path, expected, value);
  }
  return value.get<double>();
}

double JsonReader::non_negative(const json& value, const std::string& path,
                                std::string_view expected) const {
  if (!value.is_number() || !std::isfinite(value.get<double>()) || !(value.get<double>() >= 0.0)) {
    fail_expected(path, expected, value);
  }
  return value.get<double>();
}

std::int64_t JsonReader::integer(const json& value, const std::string& path,
                                 std::string_view expected) const {
  if (value.is_number_unsigned() &&
      value.get<std::uint64_t>() <=
          static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    return static_cast<std::int64_t>(value.get<std::uint64_t>());
  }
  if (value.is_number_integer() && !value.is_number_unsigned()) return value.get<std::int64_t>();
  fail_expected(path, expected, value);
}

bool JsonReader::boolean(const json& value, const std::string& path,
                         std::string_view expected) const {
  if (!value.is_boolean()) fail_expected(path, expected, value);
  return value.get<bool>();
}

InitialEquilibrium JsonReader::initial_equilibrium(const json& value, const std::string& path,
                                                   std::string_view expected) const {
  if (value.is_boolean()) return value.get<bool>() ? InitialEquilibrium::strict : InitialEquilibrium::off;
  if (value.is_string() && value.get_ref<const std::string&>() == "auto") return InitialEquilibrium::automatic;
  fail_expected(path, expected, value);
}

const std::string& JsonReader::string(const json& value, const std::string& path,
                                      std::string_view expected) const {
  if (!value.is_string()) fail_expected(path, expected, value);
  return value.get_ref<const std::string&>();
}

std::vector<double> JsonReader::numbers(const json& value, const std::string& path,
                                        std::size_t count, std::string_view expected) const {
  if (!value.is_array() || value.size() != count) fail_expected(path, expected, value);
  std::vector<double> result;
  result.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const json& item = value[i];
    if (!item.is_number() || !std::isfinite(item.get<double>())) {
      fail_expected(json_element(path, i), "a finite number", item);
    }
    result.push_back(item.get<double>());
  }
  return result;
}

std::vector<kernel::Point2> JsonReader::polygon(const json& value, const std::string& path,
                                                std::string_view expected) const {
  if (!value.is_array()) fail_expected(path, expected, value);
  std::vector<kernel::Point2> vertices;
  vertices.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    const json& v = value[i];
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
      fail_expected(json_element(path, i), "a vertex, an [x, y] pair of numbers", v);
    }
    vertices.push_back({v[0].get<double>(), v[1].get<double>()});
  }
  return vertices;
}

PolyhedronSpec JsonReader::polyhedron(const json& value, const std::string& path,
                                      std::string_view expected) const {
  static constexpr JsonField fields[] = {
      {"vertices", true, "an array of [x, y, z] vertices, m"},
      {"faces", true, "an array of faces, each an array of vertex indices counter-clockwise seen from outside"},
  };
  check_object(value, path, expected, fields);
  PolyhedronSpec spec;
  const json& vertices = value.at("vertices");
  const std::string vertices_path = json_child(path, "vertices");
  if (!vertices.is_array()) fail_expected(vertices_path, json_field(fields, "vertices").expected, vertices);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const json& v = vertices[i];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number()) {
      fail_expected(json_element(vertices_path, i), "a vertex, an [x, y, z] triple of numbers", v);
    }
    spec.vertices.push_back({v[0].get<double>(), v[1].get<double>(), v[2].get<double>()});
  }
  const json& faces = value.at("faces");
  const std::string faces_path = json_child(path, "faces");
  if (!faces.is_array()) fail_expected(faces_path, json_field(fields, "faces").expected, faces);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const json& face = faces[f];
    const std::string face_path = json_element(faces_path, f);
    if (!face.is_array()) fail_expected(face_path, "a face, an array of vertex indices", face);
    std::vector<std::uint32_t>& loop = spec.faces.emplace_back();
    for (std::size_t k = 0; k < face.size(); ++k) {
      const json& index = face[k];
      const bool valid = index.is_number_unsigned()
                             ? index.get<std::uint64_t>() <= std::numeric_limits<std::uint32_t>::max()
                             : index.is_number_integer() && index.get<std::int64_t>() >= 0;
      if (!valid) fail_expected(json_element(face_path, k), "a vertex index, an integer >= 0", index);
      loop.push_back(static_cast<std::uint32_t>(index.get<std::uint64_t>()));
    }
  }
  return spec;
}

void UniqueIds::add(const JsonReader& reader, const std::string& array_path, std::size_t index,
                    const std::string& id) {
  const auto [it, inserted] = first_index_.emplace(id, index);
  if (!inserted) {
    reader.fail(json_child(json_element(array_path, index), "id"),
                "duplicate id \"" + id + "\" (also " + json_element(array_path, it->second) +
                    ".id); expected ids unique within the file");
  }
}

Material read_material(const JsonReader& reader, const json& value, const std::string& path) {
  static constexpr JsonField fields[] = {
      {"density", true, "the density in kg/m³, a finite number > 0"},
      {"youngs_modulus", true, "Young's modulus in Pa, a finite number > 0"},
      {"poisson_ratio", true, "Poisson's ratio, a number in (-1, 0.5)"},
  };
  reader.check_object(value, path, "a material {\"density\", \"youngs_modulus\", \"poisson_ratio\"}", fields);
  Material m;
  m.density = reader.positive(value.at("density"), json_child(path, "density"), json_field(fields, "density").expected);
  m.youngs_modulus = reader.positive(value.at("youngs_modulus"), json_child(path, "youngs_modulus"),
                                     json_field(fields, "youngs_modulus").expected);
  const std::string nu_path = json_child(path, "poisson_ratio");
  const std::string_view nu_expected = json_field(fields, "poisson_ratio").expected;
  m.poisson_ratio = reader.number(value.at("poisson_ratio"), nu_path, nu_expected);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    reader.fail_expected(nu_path, nu_expected, value.at("poisson_ratio"));
  }
  return m;
}

SceneTime read_scene_time(const JsonReader& reader, const json& value, std::string_view expected,
                          std::span<const JsonField> fields) {
  reader.check_object(value, "time", expected, fields);
  SceneTime time;
  time.dt = reader.positive(value.at("dt"), "time.dt", json_field(fields, "dt").expected);
  time.duration = reader.positive(value.at("duration"), "time.duration",
                                  json_field(fields, "duration").expected);
  constexpr double max_steps = 1e12;
  if (!(time.duration / time.dt <= max_steps)) {
    reader.fail("time", "duration / dt = " + json(time.duration / time.dt).dump() +
                            " steps; expected at most 1e12 steps");
  }
  return time;
}

SceneOutput read_scene_output(const JsonReader& reader, const json& document,
                              std::span<const std::string> ids,
                              std::vector<std::string> default_track) {
  static constexpr JsonField fields[] = {
      {"track", false, "an array of block ids"},
      {"every", false, "the recording interval in steps, an integer >= 1"},
  };
  const json no_output = json::object();
  const json& value = document.contains("output") ? document.at("output") : no_output;
  reader.check_object(value, "output", "an object {\"track\", \"every\"}", fields);
  SceneOutput output;
  if (value.contains("every")) {
    const std::string_view what = json_field(fields, "every").expected;
    const std::int64_t every = reader.integer(value.at("every"), "output.every", what);
    if (every < 1) reader.fail_expected("output.every", what, value.at("every"));
    output.every = static_cast<std::size_t>(every);
  }
  if (!value.contains("track")) {
    output.track = std::move(default_track);
    return output;
  }
  const json& track = value.at("track");
  if (!track.is_array())
    reader.fail_expected("output.track", json_field(fields, "track").expected, track);
  for (std::size_t i = 0; i < track.size(); ++i) {
    const std::string item_path = json_element("output.track", i);
    const std::string& id = reader.string(track[i], item_path, "a block id");
    if (std::find(ids.begin(), ids.end(), id) == ids.end())
      reader.fail(item_path, "no block has the id \"" + id + "\"; expected a block id");
    if (std::find(output.track.begin(), output.track.end(), id) != output.track.end())
      reader.fail(item_path, "block \"" + id + "\" is listed twice; expected each id once");
    output.track.push_back(id);
  }
  return output;
}

}  // namespace rockcontact::dynamics
