#include "rockcontact/dynamics/io/scene_cdem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/scene.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;

constexpr std::string_view scene_format = "rockcontact-scene/1";

constexpr JsonField scene_fields[] = {
    {"format", false, "\"rockcontact-scene/1\""},
    {"description", false, "a string"},
    {"dimension", false, "2 (CDEM scenes are plane)"},
    {"solver", true, "\"cdem\""},
    {"time", true, "an object {\"dt\", \"duration\"}"},
    {"gravity", false, "the gravity [gx, gy] in m/s², two finite numbers"},
    {"plane", false, "one of \"strain\", \"stress\""},
    {"thickness", false, "the out-of-plane thickness in m, a finite number > 0"},
    {"damping", false, "the mass-proportional damping in 1/s, a finite number >= 0"},
    {"materials", true,
     "a non-empty object {name: {\"density\", \"youngs_modulus\", \"poisson_ratio\"}, ...}"},
    {"contact", true, "an object {\"law\", \"search_tolerance\", ...}"},
    {"blocks", true,
     "a non-empty array of blocks {\"id\", \"material\", \"vertices\", \"mesh\", ...}"},
    {"output", false, "an object {\"track\", \"every\"}"},
};
constexpr JsonField time_fields[] = {
    {"dt", true, "the time step in s, a finite number > 0"},
    {"duration", true, "the simulated time in s, a finite number > 0"},
};
constexpr JsonField contact_fields[] = {
    {"law", true,
     "one of \"two-scale\" (seed 003's clone nodes), \"penalty\" (node-to-edge springs)"},
    {"friction_angle_deg", false, "the friction angle in degrees, a number in [0, 90)"},
    {"cohesion", false, "the cohesion in Pa, a finite number >= 0"},
    {"tensile_strength", false, "the tensile strength in Pa, a finite number >= 0"},
    {"search_tolerance", true,
     "the distance in m below which a node and an edge are watched, a finite number > 0"},
    {"kn", false, "the normal penalty kn in N/m per node, a finite number > 0"},
    {"kt", false, "the tangential penalty kt in N/m per node, a finite number > 0"},
    {"subdivide", false, "true or false: subdivided elements at the clone nodes"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
};
constexpr JsonField block_fields[] = {
    {"id", true, "a non-empty string, unique within the scene"},
    {"material", true, "the name of one of the scene's materials"},
    {"vertices", true,
     "the block's outline, an array of at least 3 [x, y] vertices in m, counter-clockwise"},
    {"mesh", true, "the block's mesh size, an object {\"max_edge\": m > 0}"},
    {"fixed", false, "true or false"},
    {"velocity", false,
     "the mass centre's velocity [vx, vy, omega] in m/s and rad/s, three finite numbers"},
};
constexpr JsonField mesh_fields[] = {
    {"max_edge", true, "the longest element edge in m, a finite number > 0"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

std::optional<CdemPlane> parse_plane(std::string_view text) {
  if (text == "strain") return CdemPlane::strain;
  if (text == "stress") return CdemPlane::stress;
  return std::nullopt;
}

std::optional<CdemLaw> parse_law(std::string_view text) {
  if (text == "two-scale") return CdemLaw::two_scale;
  if (text == "penalty") return CdemLaw::penalty;
  return std::nullopt;
}

// A document being parsed: the reader (source name) plus the materials the blocks refer to.
class SceneCdemParser {
 public:
  explicit SceneCdemParser(const std::string& source) : reader_(source) {}

  void header(const json& document, SceneCdem& scene) const {
    if (!document.is_object()) {
      reader_.fail_expected(
          "", "a JSON object {\"solver\": \"cdem\", \"time\", \"blocks\", ...}", document);
    }
    reader_.check_object(document, "", "a CDEM scene object", scene_fields);
    if (document.at("solver") != "cdem")
      reader_.fail_expected("solver", expected(scene_fields, "solver"), document.at("solver"));
    if (document.contains("format")) {
      const json& value = document.at("format");
      if (!value.is_string() || value.get_ref<const std::string&>() != scene_format)
        reader_.fail_expected("format", expected(scene_fields, "format"), value);
    }
    if (document.contains("dimension") && document.at("dimension") != 2) {
      reader_.fail_expected("dimension", expected(scene_fields, "dimension"),
                            document.at("dimension"));
    }
    if (document.contains("description")) {
      scene.description = reader_.string(document.at("description"), "description",
                                         expected(scene_fields, "description"));
    }
  }

  void time(const json& value, SceneCdem& scene) const {
    const SceneTime time =
        read_scene_time(reader_, value, expected(scene_fields, "time"), time_fields);
    scene.params.dt = time.dt;
    scene.duration = time.duration;
  }

  // gravity, plane, thickness, damping.
  void physics(const json& document, SceneCdem& scene) const {
    CdemParams& params = scene.params;
    params.gravity = {0.0, -9.81};  // the 2D scene's default (scene.hpp)
    if (document.contains("gravity")) {
      const auto g =
          reader_.numbers(document.at("gravity"), "gravity", 2, expected(scene_fields, "gravity"));
      params.gravity = {g[0], g[1]};
    }
    if (document.contains("plane")) {
      params.plane = reader_.choice(document.at("plane"), "plane", expected(scene_fields, "plane"),
                                    &parse_plane);
    }
    if (document.contains("thickness")) {
      params.thickness = reader_.positive(document.at("thickness"), "thickness",
                                          expected(scene_fields, "thickness"));
    }
    if (document.contains("damping")) {
      params.damping = reader_.non_negative(document.at("damping"), "damping",
                                            expected(scene_fields, "damping"));
    }
  }

  void materials(const json& value) {
    if (!value.is_object() || value.empty())
      reader_.fail_expected("materials", expected(scene_fields, "materials"), value);
    for (const auto& [name, item] : value.items()) {
      const Material m = read_material(reader_, item, json_child("materials", name));
      materials_.emplace(name, CdemMaterial{m.density, m.youngs_modulus, m.poisson_ratio});
    }
  }

  void contact(const json& value, SceneCdem& scene) const {
    reader_.check_object(value, "contact", expected(scene_fields, "contact"), contact_fields);
    CdemContactParams& c = scene.params.contact;
    c.law = reader_.choice(value.at("law"), "contact.law", expected(contact_fields, "law"),
                           &parse_law);
    law_fields(value, c.law);
    if (value.contains("friction_angle_deg")) {
      const std::string_view what = expected(contact_fields, "friction_angle_deg");
      const json& phi = value.at("friction_angle_deg");
      c.friction_angle_deg = reader_.non_negative(phi, "contact.friction_angle_deg", what);
      if (!(c.friction_angle_deg < 90.0))
        reader_.fail_expected("contact.friction_angle_deg", what, phi);
    }
    for (auto [key, target] : {std::pair{"cohesion", &c.cohesion},
                               std::pair{"tensile_strength", &c.tensile_strength}}) {
      if (value.contains(key)) {
        *target = reader_.non_negative(value.at(key), json_child("contact", key),
                                       expected(contact_fields, key));
      }
    }
    c.search_tolerance = reader_.positive(value.at("search_tolerance"), "contact.search_tolerance",
                                          expected(contact_fields, "search_tolerance"));
    if (value.contains("policy")) {
      c.policy = reader_.choice(value.at("policy"), "contact.policy",
                                expected(contact_fields, "policy"), &kernel::parse_policy);
    }
    if (c.law == CdemLaw::penalty) {
      c.kn = reader_.positive(value.at("kn"), "contact.kn", expected(contact_fields, "kn"));
      c.kt = value.contains("kt")
                 ? reader_.positive(value.at("kt"), "contact.kt", expected(contact_fields, "kt"))
                 : c.kn;
    } else if (value.contains("subdivide")) {
      c.subdivide = reader_.boolean(value.at("subdivide"), "contact.subdivide",
                                    expected(contact_fields, "subdivide"));
    }
  }

  void blocks(const json& value, SceneCdem& scene) const {
    if (!value.is_array() || value.empty())
      reader_.fail_expected("blocks", expected(scene_fields, "blocks"), value);
    UniqueIds ids;
    for (std::size_t i = 0; i < value.size(); ++i) {
      scene.blocks.push_back(block(value[i], json_element("blocks", i)));
      ids.add(reader_, "blocks", i, scene.blocks.back().id);
    }
  }

  void output(const json& document, SceneCdem& scene) const {
    SceneOutput output = read_scene_output(reader_, document, scene.blocks);
    scene.track = std::move(output.track);
    scene.every = output.every;
  }

 private:
  // The fields one law has and the other has not: kn (required), kt for penalty springs;
  // subdivide for clone nodes.
  void law_fields(const json& value, CdemLaw law) const {
    if (law == CdemLaw::penalty) {
      if (!value.contains("kn")) {
        reader_.fail("contact.kn", "missing field; expected " +
                                       std::string(expected(contact_fields, "kn")) +
                                       " (the penalty law needs it)");
      }
      if (value.contains("subdivide")) {
        reader_.fail("contact.subdivide",
                     "subdivided elements belong to the two-scale law; expected no "
                     "\"subdivide\" with \"law\": \"penalty\"");
      }
      return;
    }
    for (const char* key : {"kn", "kt"}) {
      if (value.contains(key)) {
        reader_.fail(json_child("contact", key),
                     std::string("the stiffness ") + key +
                         " belongs to the penalty law; expected no \"" + key +
                         "\" with \"law\": \"two-scale\" (its clone nodes need no stiffness)");
      }
    }
  }

  CdemBlockSpec block(const json& value, const std::string& path) const {
    reader_.check_object(
        value, path, "a block, an object {\"id\", \"material\", \"vertices\", \"mesh\", ...}",
        block_fields);
    CdemBlockSpec spec;
    const std::string id_path = json_child(path, "id");
    spec.id = reader_.string(value.at("id"), id_path, expected(block_fields, "id"));
    if (spec.id.empty())
      reader_.fail_expected(id_path, expected(block_fields, "id"), value.at("id"));
    spec.material = material_of(value.at("material"), json_child(path, "material"));
    spec.vertices = vertices(value.at("vertices"), json_child(path, "vertices"));
    const std::string mesh_path = json_child(path, "mesh");
    const json& mesh = value.at("mesh");
    reader_.check_object(mesh, mesh_path, expected(block_fields, "mesh"), mesh_fields);
    spec.max_edge = reader_.positive(mesh.at("max_edge"), json_child(mesh_path, "max_edge"),
                                     expected(mesh_fields, "max_edge"));
    if (value.contains("fixed")) {
      spec.fixed = reader_.boolean(value.at("fixed"), json_child(path, "fixed"),
                                   expected(block_fields, "fixed"));
    }
    if (value.contains("velocity")) {
      const std::string velocity_path = json_child(path, "velocity");
      if (spec.fixed)
        reader_.fail(velocity_path, "a fixed block does not move; expected no velocity on it");
      const auto v = reader_.numbers(value.at("velocity"), velocity_path, 3,
                                     expected(block_fields, "velocity"));
      std::copy(v.begin(), v.end(), spec.velocity.begin());
    }
    return spec;
  }

  // At least 3 vertices of finite coordinates; the polygon itself is the mesher's to check.
  std::vector<kernel::Point2> vertices(const json& value, const std::string& path) const {
    const std::string_view what = expected(block_fields, "vertices");
    std::vector<kernel::Point2> points = reader_.polygon(value, path, what);
    if (points.size() < 3) reader_.fail_expected(path, what, value);
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (!std::isfinite(points[k].x) || !std::isfinite(points[k].y)) {
        reader_.fail_expected(json_element(path, k), "a vertex, an [x, y] pair of finite numbers",
                              value[k]);
      }
    }
    return points;
  }

  CdemMaterial material_of(const json& value, const std::string& path) const {
    return find_material(reader_, value, path, expected(block_fields, "material"), materials_);
  }

  JsonReader reader_;
  std::map<std::string, CdemMaterial, std::less<>> materials_;
};

}  // namespace

bool is_scene_cdem_document(const json& document) {
  return document.is_object() && document.contains("solver") && document.at("solver") == "cdem";
}

SceneCdem parse_scene_cdem(const json& document, const std::string& source) {
  SceneCdemParser parser(source);
  SceneCdem scene;
  scene.source = source;
  parser.header(document, scene);
  parser.time(document.at("time"), scene);
  parser.physics(document, scene);
  parser.materials(document.at("materials"));
  parser.contact(document.at("contact"), scene);
  parser.blocks(document.at("blocks"), scene);
  parser.output(document, scene);
  return scene;
}

SceneCdem read_scene_cdem_file(const std::filesystem::path& file) {
  return parse_scene_cdem(read_json_file(file), file.string());
}

std::size_t step_count(const SceneCdem& scene) {
  return step_count(scene.duration, scene.params.dt);
}

}  // namespace rockcontact::dynamics
