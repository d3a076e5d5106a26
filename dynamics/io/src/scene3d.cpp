#include "rockcontact/dynamics/io/scene3d.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "rockcontact/dynamics/io/cut3d.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;

constexpr std::string_view scene_format = "rockcontact-scene/1";

constexpr JsonField scene_fields[] = {
    {"format", false, "\"rockcontact-scene/1\""},
    {"description", false, "a string"},
    {"dimension", true, "3"},
    {"time", true, "an object {\"dt\", \"duration\", \"max_displacement_ratio\", \"max_rotation_deg\"}"},
    {"gravity", false, "the gravity [gx, gy, gz] in m/s², three finite numbers"},
    {"initial_equilibrium", false,
     "\"auto\", true or false: settle the blocks resting at the start before the run; \"auto\" "
     "(the default) starts the blocks without a static state from their given state, true "
     "refuses them"},
    {"analysis", false, "one of \"dynamic\", \"static\" (velocities zeroed after every step)"},
    {"materials", true,
     "an object {name: {\"density\", \"youngs_modulus\", \"poisson_ratio\"}, ...}"},
    {"contact", true, "an object {\"law\": \"penalty\", \"kn\", \"kt\", ...}"},
    {"interfaces", false, "an array of interfaces {\"between\": [group, group], ...}"},
    {"blocks", false, "an array of blocks {\"id\", \"material\", \"vertices\", \"faces\", ...}"},
    {"region", false,
     "a region {\"vertices\", \"faces\"}, {\"box\"} or {\"parts\"} with \"material\", cut by the "
     "joint sets"},
    {"joint_sets", false,
     "an array of joint sets {\"dip_deg\", \"dip_direction_deg\", \"spacing\", \"offset\"}"},
    {"output", false, "an object {\"track\", \"every\"}"},
};
constexpr JsonField time_fields[] = {
    {"dt", true, "the largest time step in s, a finite number > 0"},
    {"duration", true, "the simulated time in s, a finite number > 0"},
    {"max_displacement_ratio", false,
     "the largest vertex displacement of a step over the scene's size, a number in (0, 1)"},
    {"max_rotation_deg", false, "the largest rotation of a block in a step, degrees, a number in (0, 90)"},
};
constexpr JsonField contact_fields[] = {
    {"law", true, "\"penalty\" (the generalized penalty contact of seed 001)"},
    {"kn", false,
     "the normal penalty kn in N/m per constraint, a finite number > 0, or \"auto\" (the default: 10 E L "
     "of the smallest movable block)"},
    {"kt", false,
     "the tangential penalty kt in N/m per constraint, a finite number > 0, or \"auto\" (the default: kn / "
     "10)"},
    {"friction_angle_deg", false, "the friction angle in degrees, a number in [0, 90)"},
    {"cohesion", false, "the cohesion in Pa, a finite number >= 0"},
    {"tensile_strength", false, "the tensile strength in Pa, a finite number >= 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"damping_ratio", false, "the contact dashpots' critical damping ratio, a finite number >= 0"},
};
constexpr JsonField interface_fields[] = {
    {"between", true, "the two group names [group, group], strings"},
    {"friction_angle_deg", false, "the friction angle in degrees, a number in [0, 90)"},
    {"cohesion", false, "the cohesion in Pa, a finite number >= 0 (default contact.cohesion)"},
    {"tensile_strength", false,
     "the tensile strength in Pa, a finite number >= 0 (default contact.tensile_strength)"},
};
constexpr JsonField block_fields[] = {
    {"id", true, "a non-empty string, unique within the scene"},
    {"material", true, "the name of one of the scene's materials"},
    {"vertices", false, "the block's vertices, an array of [x, y, z] in m (with \"faces\")"},
    {"faces", false,
     "the block's faces, arrays of vertex indices counter-clockwise seen from outside (with "
     "\"vertices\")"},
    {"parts", false,
     "the convex parts of a non-convex block, an array of {\"vertices\", \"faces\"}"},
    {"group", false, "a group name (a string) that interfaces refer to"},
    {"fixed", false, "true or false"},
    {"rigid", false, "true or false"},
    {"velocity", false,
     "the centroid velocity [vx, vy, vz, wx, wy, wz] in m/s and rad/s, six finite numbers"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

// Where an InvalidPolyhedron belongs: the face it names, else the vertex, else the solid.
std::string polyhedron_error_path(const std::string& path, const kernel::InvalidPolyhedron& e) {
  if (e.face() >= 0)
    return json_element(json_child(path, "faces"), static_cast<std::size_t>(e.face()));
  if (e.vertex() >= 0) {
    return json_element(json_child(path, "vertices"), static_cast<std::size_t>(e.vertex()));
  }
  return path;
}

// Does every vertex lie in one plane (exactly, orient3d)? The solid then has no volume, which
// the kernel reports as a vertex on a face's plane.
bool flat(std::span<const kernel::Point3> v) {
  for (std::size_t j = 1; j < v.size(); ++j) {
    for (std::size_t k = j + 1; k < v.size(); ++k) {
      for (std::size_t l = k + 1; l < v.size(); ++l) {
        if (kernel::orient3d<kernel::Filtered>(v[0], v[j], v[k], v[l]) != kernel::Sign::zero)
          return false;
      }
    }
  }
  return true;
}

// A document being parsed: the reader (source name) plus the materials later fields refer to.
class Scene3dParser {
 public:
  explicit Scene3dParser(const std::string& source) : reader_(source) {}

  void header(const json& document, Scene3d& scene) const {
    if (!document.is_object()) {
      reader_.fail_expected("", "a JSON object {\"dimension\": 3, \"time\", \"blocks\", ...}",
                            document);
    }
    if (document.contains("format")) {
      const json& value = document.at("format");
      if (!value.is_string() || value.get_ref<const std::string&>() != scene_format) {
        reader_.fail_expected("format", expected(scene_fields, "format"), value);
      }
    }
    if (!document.contains("dimension") || document.at("dimension") != 3) {
      reader_.fail_expected("dimension", "3",
                            document.contains("dimension") ? document.at("dimension") : json());
    }
    reader_.check_object(document, "", "a 3D scene object", scene_fields);
    if (document.contains("description")) {
      scene.description = reader_.string(document.at("description"), "description",
                                         expected(scene_fields, "description"));
    }
  }

  void time(const json& value, Scene3d& scene) const {
    const SceneTime time =
        read_scene_time(reader_, value, expected(scene_fields, "time"), time_fields);
    scene.params.dt = time.dt;
    scene.duration = time.duration;
    below(value, "max_displacement_ratio", 1.0, scene.params.max_displacement_ratio);
    below(value, "max_rotation_deg", 90.0, scene.params.max_rotation_deg);
  }

  // The optional time field `name`, a number in (0, bound), into `out`.
  void below(const json& time, const char* name, double bound, double& out) const {
    if (!time.contains(name)) return;
    const std::string path = std::string("time.") + name;
    const std::string_view what = expected(time_fields, name);
    const double x = reader_.positive(time.at(name), path, what);
    if (!(x < bound)) reader_.fail_expected(path, what, time.at(name));
    out = x;
  }

  void gravity(const json& document, Scene3d& scene) const {
    if (!document.contains("gravity")) return;
    const auto g =
        reader_.numbers(document.at("gravity"), "gravity", 3, expected(scene_fields, "gravity"));
    scene.params.gravity = {g[0], g[1], g[2]};
  }

  void analysis(const json& document, Scene3d& scene) const {
    if (document.contains("initial_equilibrium")) {
      scene.params.initial_equilibrium = reader_.initial_equilibrium(document.at("initial_equilibrium"), "initial_equilibrium",
                                                         expected(scene_fields, "initial_equilibrium"));
    }
    if (document.contains("analysis")) {
      scene.params.static_analysis =
          reader_.choice<bool>(document.at("analysis"), "analysis", expected(scene_fields, "analysis"),
                         +[](std::string_view text) -> std::optional<bool> {
                           if (text == "dynamic") return false;
                           if (text == "static") return true;
                           return std::nullopt;
                         });
    }
  }

  void materials(const json& value) {
    if (!value.is_object())
      reader_.fail_expected("materials", expected(scene_fields, "materials"), value);
    for (const auto& [name, item] : value.items()) materials_.emplace(name, material(item, name));
  }

  void contact(const json& value, Scene3d& scene) const {
    reader_.check_object(value, "contact", expected(scene_fields, "contact"), contact_fields);
    if (reader_.string(value.at("law"), "contact.law", expected(contact_fields, "law")) !=
        "penalty") {
      reader_.fail_expected("contact.law", expected(contact_fields, "law"), value.at("law"));
    }
    ContactLaw3d& law = scene.law;
    scene.kn_auto = penalty(value, "kn", law.kn);
    scene.kt_auto = penalty(value, "kt", law.kt);
    law.friction_angle_deg = friction_angle(value, "contact", contact_fields, 0.0);
    law.cohesion = strength(value, "contact", "cohesion", contact_fields, 0.0);
    law.tensile_strength = strength(value, "contact", "tensile_strength", contact_fields, 0.0);
    if (value.contains("damping_ratio")) {
      law.damping_ratio = reader_.non_negative(value.at("damping_ratio"), "contact.damping_ratio",
                                               expected(contact_fields, "damping_ratio"));
    }
    if (value.contains("policy")) {
      law.policy = reader_.choice(value.at("policy"), "contact.policy",
                                  expected(contact_fields, "policy"), &kernel::parse_policy);
    }
  }

  void blocks(const json& document, Scene3d& scene) const {
    if (!document.contains("blocks")) return;
    const json& value = document.at("blocks");
    if (!value.is_array()) reader_.fail_expected("blocks", expected(scene_fields, "blocks"), value);
    UniqueIds ids;
    for (std::size_t i = 0; i < value.size(); ++i) {
      const std::string path = json_element("blocks", i);
      scene.blocks.push_back(block(value[i], path));
      scene.material_names.push_back(value[i].at("material").get<std::string>());
      ids.add(reader_, "blocks", i, scene.blocks.back().id);
    }
  }

  // The region cut by the joint sets as `rockcontact cut` cuts it (cut3d.hpp): the same fields
  // at the same paths, so its messages name the scene's fields.
  void region(const json& document, Scene3d& scene) const {
    if (!document.contains("region")) {
      if (document.contains("joint_sets")) {
        reader_.fail("joint_sets", "joint sets cut a region; expected a \"region\" beside them");
      }
      return;
    }
    json cut_document = {{"dimension", 3}, {"region", document.at("region")}};
    if (document.contains("joint_sets")) cut_document["joint_sets"] = document.at("joint_sets");
    const Cut3Input input = parse_cut3(cut_document, reader_.source());
    if (input.material.empty()) {
      reader_.fail("region.material",
                   "missing field; expected the name of one of the scene's materials "
                   "(the material of every block cut from the region)");
    }
    const Material material = material_of(document.at("region").at("material"), "region.material");
    Cut3Result cut = cut3d(input);
    scene.min_block_volume = cut.min_block_volume;
    scene.merged_fragments = cut.merged;
    scene.generated_first = scene.blocks.size();
    for (std::size_t k = 0; k < cut.blocks.size(); ++k) {
      Block3dSpec spec;
      spec.id = input.id_prefix + "_" + std::to_string(k + 1);
      const bool taken = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                     [&](const Block3dSpec& b) { return b.id == spec.id; });
      if (taken) {
        reader_.fail("region.id_prefix",
                     "the generated id \"" + spec.id +
                         "\" is also a block's; expected a prefix no other block id uses");
      }
      spec.parts = std::move(cut.blocks[k].parts);
      spec.group = input.group;
      spec.material = material;
      scene.blocks.push_back(std::move(spec));
      scene.material_names.push_back(input.material);
    }
    scene.generated_count = scene.blocks.size() - scene.generated_first;
  }

  void interfaces(const json& document, Scene3d& scene) const {
    if (!document.contains("interfaces")) return;
    const json& value = document.at("interfaces");
    if (!value.is_array())
      reader_.fail_expected("interfaces", expected(scene_fields, "interfaces"), value);
    for (std::size_t i = 0; i < value.size(); ++i) {
      const std::string path = json_element("interfaces", i);
      Interface3d face = interface(value[i], path, scene);
      for (std::size_t k = 0; k < i; ++k) {
        const auto& other = scene.law.interfaces[k].groups;
        if (std::minmax(other[0], other[1]) == std::minmax(face.groups[0], face.groups[1])) {
          reader_.fail(json_child(path, "between"),
                       "the groups \"" + face.groups[0] + "\" and \"" + face.groups[1] +
                           "\" already have an interface (" + json_element("interfaces", k) +
                           "); expected one per pair of groups");
        }
      }
      scene.law.interfaces.push_back(std::move(face));
    }
  }

  // Without "output" or "output.track", every block that is not fixed is tracked.
  void output(const json& document, Scene3d& scene) const {
    SceneOutput output = read_scene_output(reader_, document, scene.blocks);
    scene.track = std::move(output.track);
    scene.every = output.every;
  }

 private:
  // contact.<name>: a number > 0 into `out`, or "auto" or nothing (true: parse_scene3d sets it once
  // the blocks are read).
  bool penalty(const json& contact, const char* name, double& out) const {
    if (!contact.contains(name) || contact.at(name) == "auto") return true;
    out = reader_.positive(contact.at(name), std::string("contact.") + name, expected(contact_fields, name));
    return false;
  }

  Material material(const json& value, const std::string& name) const {
    return read_material(reader_, value, json_child("materials", name));
  }

  Material material_of(const json& value, const std::string& path) const {
    return find_material(reader_, value, path, expected(block_fields, "material"), materials_);
  }

  // friction_angle_deg of `value` at `path`, in [0, 90), or `fallback` when absent.
  double friction_angle(const json& value, const std::string& path,
                        std::span<const JsonField> fields, double fallback) const {
    if (!value.contains("friction_angle_deg")) return fallback;
    const std::string field_path = json_child(path, "friction_angle_deg");
    const std::string_view what = expected(fields, "friction_angle_deg");
    const double phi = reader_.non_negative(value.at("friction_angle_deg"), field_path, what);
    if (!(phi < 90.0)) reader_.fail_expected(field_path, what, value.at("friction_angle_deg"));
    return phi;
  }

  // A strength (cohesion, tensile_strength) of `value` at `path`, >= 0, or `fallback`.
  double strength(const json& value, const std::string& path, std::string_view field,
                  std::span<const JsonField> fields, double fallback) const {
    if (!value.contains(field)) return fallback;
    return reader_.non_negative(value.at(field), json_child(path, field), expected(fields, field));
  }

  Interface3d interface(const json& value, const std::string& path, const Scene3d& scene) const {
    reader_.check_object(
        value, path,
        "an interface {\"between\", \"friction_angle_deg\", \"cohesion\", \"tensile_strength\"}",
        interface_fields);
    const json& groups = value.at("between");
    const std::string between_path = json_child(path, "between");
    if (!groups.is_array() || groups.size() != 2 || !groups[0].is_string() ||
        !groups[1].is_string()) {
      reader_.fail_expected(between_path, expected(interface_fields, "between"), groups);
    }
    Interface3d face;
    face.groups = {groups[0].get<std::string>(), groups[1].get<std::string>()};
    // An interface whose group no block has would never act: most likely a misspelt name.
    for (std::size_t g = 0; g < 2; ++g) {
      const std::string& group = face.groups[g];
      const bool used = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                    [&](const Block3dSpec& b) { return b.group == group; });
      if (!used) {
        reader_.fail(
            json_element(between_path, g),
            "no block is in the group \"" + group + "\"; expected the group of one of the blocks");
      }
    }
    face.friction_angle_deg =
        friction_angle(value, path, interface_fields, scene.law.friction_angle_deg);
    face.cohesion = strength(value, path, "cohesion", interface_fields, scene.law.cohesion);
    face.tensile_strength =
        strength(value, path, "tensile_strength", interface_fields, scene.law.tensile_strength);
    return face;
  }

  Block3dSpec block(const json& value, const std::string& path) const {
    reader_.check_object(value, path,
                         "a block, an object {\"id\", \"material\", \"vertices\", \"faces\", ...}",
                         block_fields);
    Block3dSpec spec;
    const std::string id_path = json_child(path, "id");
    spec.id = reader_.string(value.at("id"), id_path, expected(block_fields, "id"));
    if (spec.id.empty())
      reader_.fail_expected(id_path, expected(block_fields, "id"), value.at("id"));
    spec.material = material_of(value.at("material"), json_child(path, "material"));
    if (value.contains("group")) {
      spec.group = reader_.string(value.at("group"), json_child(path, "group"),
                                  expected(block_fields, "group"));
    }
    for (auto [key, target] : {std::pair{"fixed", &spec.fixed}, std::pair{"rigid", &spec.rigid}}) {
      if (value.contains(key))
        *target =
            reader_.boolean(value.at(key), json_child(path, key), expected(block_fields, key));
    }
    if (value.contains("velocity")) {
      const std::string velocity_path = json_child(path, "velocity");
      if (spec.fixed) {
        reader_.fail(velocity_path, "a fixed block does not move; expected no velocity on it");
      }
      const auto v = reader_.numbers(value.at("velocity"), velocity_path, 6,
                                     expected(block_fields, "velocity"));
      std::copy(v.begin(), v.end(), spec.velocity.begin());
    }
    spec.parts = parts(value, path, spec.id);
    return spec;
  }

  // "vertices" with "faces" (one convex part), or "parts".
  std::vector<kernel::ConvexPolyhedron> parts(const json& value, const std::string& path,
                                              const std::string& id) const {
    const bool solid = value.contains("vertices") || value.contains("faces");
    if (solid == value.contains("parts")) {
      reader_.fail(
          path,
          "expected exactly one of \"vertices\" with \"faces\" (a convex block) or \"parts\"");
    }
    if (solid) {
      json polyhedron = json::object();
      for (const char* key : {"vertices", "faces"}) {
        if (!value.contains(key)) {
          reader_.fail(json_child(path, key),
                       "missing field; expected " + std::string(expected(block_fields, key)));
        }
        polyhedron[key] = value.at(key);
      }
      return {make(polyhedron, path, id)};
    }
    const json& list = value.at("parts");
    const std::string parts_path = json_child(path, "parts");
    if (!list.is_array() || list.empty())
      reader_.fail_expected(parts_path, expected(block_fields, "parts"), list);
    std::vector<kernel::ConvexPolyhedron> out;
    for (std::size_t j = 0; j < list.size(); ++j) {
      out.push_back(make(list[j], json_element(parts_path, j), id + "." + std::to_string(j + 1)));
    }
    return out;
  }

  kernel::ConvexPolyhedron make(const json& value, const std::string& path,
                                const std::string& name) const {
    PolyhedronSpec spec =
        reader_.polyhedron(value, path, "a convex polyhedron {\"vertices\", \"faces\"}");
    try {
      return kernel::ConvexPolyhedron::make(name, spec.vertices, std::move(spec.faces));
    } catch (const kernel::InvalidPolyhedron& e) {
      if (e.reason() == kernel::InvalidPolyhedron::Reason::not_convex && flat(spec.vertices)) {
        reader_.fail(json_child(path, "vertices"),
                     "polyhedron '" + name +
                         "': every vertex lies in one plane, zero volume; "
                         "expected a solid");
      }
      reader_.fail(polyhedron_error_path(path, e), e.what());
    }
  }

  JsonReader reader_;
  std::map<std::string, Material, std::less<>> materials_;
};

}  // namespace

bool is_scene3d_document(const json& document) {
  return document.is_object() && document.contains("dimension") && document.at("dimension") == 3;
}

Scene3d parse_scene3d(const json& document, const std::string& source_name) {
  Scene3dParser parser(source_name);
  Scene3d scene;
  scene.source = source_name;
  parser.header(document, scene);
  parser.time(document.at("time"), scene);
  parser.gravity(document, scene);
  parser.analysis(document, scene);
  parser.materials(document.at("materials"));
  parser.contact(document.at("contact"), scene);
  parser.blocks(document, scene);
  parser.region(document, scene);
  if (scene.blocks.empty()) {
    JsonReader(source_name)
        .fail("blocks", "the scene has no blocks; expected \"blocks\" or a \"region\"");
  }
  parser.interfaces(document, scene);
  parser.output(document, scene);
  if (scene.kn_auto) scene.law.kn = auto_normal_penalty3d(scene.blocks);
  if (scene.kt_auto) scene.law.kt = scene.law.kn / 10.0;
  return scene;
}

Scene3d read_scene3d_file(const std::filesystem::path& file) {
  return parse_scene3d(read_json_file(file), file.string());
}

}  // namespace rockcontact::dynamics
