#include "rockcontact/dynamics/io/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;

// The scene format this version reads ("format", optional).
constexpr std::string_view scene_format = "rockcontact-scene/1";

constexpr JsonField scene_fields[] = {
    {"format", false, "\"rockcontact-scene/1\""},
    {"description", false, "a string"},
    {"dimension", true, "2"},
    {"time", true, "an object {\"dt\", \"duration\"}"},
    {"gravity", false, "the gravity [gx, gy] in m/s², two finite numbers"},
    {"plane", false, "one of \"stress\", \"strain\""},
    {"damping", false, "the mass damping alpha in 1/s, a finite number >= 0"},
    {"initial_equilibrium", false,
     "\"auto\", true or false: settle the blocks resting at the start before the run; \"auto\" "
     "(the default) starts the blocks without a static state from their given state, true "
     "refuses them"},
    {"analysis", false, "one of \"dynamic\", \"static\""},
    {"static_tolerance", false,
     "the out-of-balance force ratio at which a static analysis stops, a number in (0, 1)"},
    {"materials", true,
     "an object {name: {\"density\", \"youngs_modulus\", \"poisson_ratio\"}, ...}"},
    {"contact", true, "an object {\"law\", \"kn\", \"H\", ...}"},
    {"blocks", false, "an array of blocks {\"id\", \"material\", \"vertices\", ...}"},
    {"region", false,
     "a region {\"vertices\", \"material\", \"group\", \"id_prefix\"} or an array of them, cut by "
     "the joint sets"},
    {"joint_sets", false, "an array of joint sets {\"dip_deg\", \"spacing\", ...}"},
    {"interfaces", false, "an array of interfaces {\"between\": [group, group], ...}"},
    {"boundaries", false, "an array of boundary segments {\"id\", \"material\", \"from\", \"to\"}"},
    {"output", false, "an object {\"track\", \"every\"}"},
};
constexpr JsonField time_fields[] = {
    {"dt", true, "the time step in s, a finite number > 0"},
    {"duration", true, "the simulated time in s, a finite number > 0"},
};
constexpr JsonField contact_fields[] = {
    {"law", true, "\"potential\" (the distance-potential contact of seed 000)"},
    {"kn", true, "the normal penalty kn in Pa, a finite number > 0"},
    {"H", true,
     "the potential length scale H: a length in m > 0, \"mean_edge\", \"mean_edge_movable\" or "
     "\"inscribed\""},
    {"kt", false, "the tangential penalty kt in N/m, a finite number > 0"},
    {"friction_angle_deg", false, "the friction angle in degrees, a number in [0, 90)"},
    {"friction", false,
     "the friction law, one of \"elastoplastic\", \"paper\" (with kt and friction_angle_deg)"},
    {"cohesion", false, "the cohesion in Pa, a finite number >= 0 (with kt and friction_angle_deg)"},
    {"damping_ratio", false, "the contact dashpots' critical damping ratio, a finite number >= 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"demarcation", false, "one of \"paper\", \"exact\""},
};
constexpr JsonField block_fields[] = {
    {"id", true, "a non-empty string, unique within the scene"},
    {"material", true, "the name of one of the scene's materials"},
    {"vertices", true, "the block's polygon, an array of [x, y] vertices in m, CCW"},
    {"fixed", false, "true or false"},
    {"rigid", false, "true or false"},
    {"velocity", false, "the centroid velocity [vx, vy, omega] in m/s, m/s, rad/s"},
    {"group", false, "a group name (a string) that interfaces refer to"},
};
constexpr JsonField region_fields[] = {
    {"vertices", true, "the region's polygon, an array of [x, y] vertices in m, CCW, simple"},
    {"material", true, "the name of one of the scene's materials"},
    {"group", false, "the group name of the generated blocks (a string)"},
    {"id_prefix", false, "the prefix of the generated block ids (a string, default \"region\")"},
    {"min_block_area", false,
     "the area in m² below which a cut block is merged into a neighbour, a finite number >= 0"},
};
constexpr JsonField joint_set_fields[] = {
    {"dip_deg", true, "the trace angle from +x, counter-clockwise, in degrees, a number in [0, 180)"},
    {"spacing", true, "the spacing of the traces in m, a finite number > 0"},
    {"offset", false, "the offset of the traces along their normal in m, a finite number"},
    {"length", false, "the trace length in m, a finite number > 0 (default: persistent traces)"},
    {"gap", false, "the gap between traces along a line in m, a finite number >= 0 (with length)"},
};
constexpr JsonField interface_fields[] = {
    {"between", true, "the two groups [group, group] (strings; the order does not matter)"},
    {"kn", false, "the normal penalty kn in Pa, a finite number > 0 (default contact.kn)"},
    {"kt", false, "the tangential penalty kt in N/m, a finite number > 0 (default contact.kt)"},
    {"friction_angle_deg", false, "the friction angle in degrees, a number in [0, 90)"},
    {"cohesion", false, "the cohesion in Pa, a finite number >= 0 (default contact.cohesion)"},
};
constexpr JsonField boundary_fields[] = {
    {"id", true, "a non-empty string, unique among blocks and boundaries"},
    {"material", true, "the name of one of the scene's materials"},
    {"from", true, "the segment's first end [x, y] in m"},
    {"to", true, "the segment's second end [x, y] in m, not equal to from"},
    {"depth", false, "the depth of the fixed polygon behind the segment in m, a finite number > 0"},
    {"group", false, "a group name (a string) that interfaces refer to"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

std::optional<PlaneMode> parse_plane(std::string_view text) {
  if (text == "stress") return PlaneMode::stress;
  if (text == "strain") return PlaneMode::strain;
  return std::nullopt;
}

std::optional<Analysis> parse_analysis(std::string_view text) {
  if (text == "dynamic") return Analysis::dynamic;
  if (text == "static") return Analysis::static_equilibrium;
  return std::nullopt;
}

std::optional<HRule> parse_h_rule(std::string_view text) {
  if (text == "mean_edge") return HRule::mean_edge;
  if (text == "mean_edge_movable") return HRule::mean_edge_movable;
  if (text == "inscribed") return HRule::inscribed;
  return std::nullopt;
}

using Materials = std::map<std::string, Material, std::less<>>;

// Where in the scene a kernel::cut_region refusal belongs: its subject in the kernel's terms
// ("region", "joint_sets[i].FIELD" with "trace_length" for the scene's "length",
// "min_block_area", "block near (x, y)") mapped onto the JSON path, so the error reads
// "<file>: region.vertices: vertices are clockwise ..." rather than naming the region twice.
std::string cut_error_path(const std::string& region_path, const kernel::InvalidCut& e) {
  const std::string& subject = e.subject();
  if (subject == "region") return json_child(region_path, "vertices");
  if (subject == "min_block_area") return json_child(region_path, "min_block_area");
  if (subject.rfind("joint_sets[", 0) == 0) {
    const std::size_t at = subject.find(".trace_length");
    return at == std::string::npos ? subject : subject.substr(0, at) + ".length";
  }
  return region_path;  // a block the cut would make
}


// A document being parsed: the reader (source name) plus what later fields refer to.
class SceneParser {
 public:
  explicit SceneParser(const std::string& source) : reader_(source) {}

  // "rockcontact-scene/N": only N = 1 is read; a later N names the version it needs.
  void format(const json& document) const {
    if (!document.contains("format")) return;
    const json& value = document.at("format");
    const std::string_view prefix = "rockcontact-scene/";
    if (value.is_string() && value.get_ref<const std::string&>() == scene_format) return;
    if (value.is_string() && value.get_ref<const std::string&>().starts_with(prefix)) {
      reader_.fail("format", "the scene is written in format " + value.get<std::string>() +
                                 "; this rockcontact reads " + std::string(scene_format) +
                                 ": read it with the version that wrote it, or rewrite it");
    }
    reader_.fail_expected("format", expected(scene_fields, "format"), value);
  }

  void dimension(const json& document) const {
    if (!document.contains("dimension")) {
      reader_.fail("dimension", "missing field; expected 2");
    }
    const json& value = document.at("dimension");
    if (value.is_number_integer() && value.get<std::int64_t>() == 3) {
      reader_.fail("dimension", "a 3D scene, read by parse_scene3d (scene3d.hpp); expected 2 here");
    }
    if (!value.is_number_integer() || value.get<std::int64_t>() != 2) {
      reader_.fail_expected("dimension", "2", value);
    }
  }

  void time(const json& value, Scene& scene) const {
    const SceneTime time =
        read_scene_time(reader_, value, expected(scene_fields, "time"), time_fields);
    scene.params.dt = time.dt;
    scene.duration = time.duration;
  }

  void physics(const json& document, Scene& scene) const {
    if (document.contains("gravity")) {
      const auto g =
          reader_.numbers(document.at("gravity"), "gravity", 2, expected(scene_fields, "gravity"));
      scene.params.gravity = {g[0], g[1]};
    }
    if (document.contains("plane")) {
      scene.params.plane = reader_.choice(document.at("plane"), "plane",
                                          expected(scene_fields, "plane"), &parse_plane);
    }
    if (document.contains("damping")) {
      scene.params.mass_damping = reader_.non_negative(document.at("damping"), "damping",
                                                       expected(scene_fields, "damping"));
    }
    if (document.contains("analysis")) {
      scene.params.analysis = reader_.choice(document.at("analysis"), "analysis",
                                             expected(scene_fields, "analysis"), &parse_analysis);
    }
    if (document.contains("static_tolerance")) {
      const std::string_view what = expected(scene_fields, "static_tolerance");
      scene.static_tolerance = reader_.positive(document.at("static_tolerance"), "static_tolerance", what);
      if (!(scene.static_tolerance < 1.0)) {
        reader_.fail_expected("static_tolerance", what, document.at("static_tolerance"));
      }
    }
    if (document.contains("initial_equilibrium")) {
      scene.params.initial_equilibrium =
          reader_.initial_equilibrium(document.at("initial_equilibrium"), "initial_equilibrium",
                                      expected(scene_fields, "initial_equilibrium"));
    }
  }

  void materials(const json& value) {
    if (!value.is_object()) {
      reader_.fail_expected("materials", expected(scene_fields, "materials"), value);
    }
    for (const auto& [name, item] : value.items()) materials_.emplace(name, material(item, name));
  }

  // Leaves law.normal.H for resolve_h, once the blocks are known.
  void contact(const json& value, Scene& scene) {
    const std::string path = "contact";
    reader_.check_object(value, path, expected(scene_fields, "contact"), contact_fields);
    if (reader_.string(value.at("law"), "contact.law", expected(contact_fields, "law")) !=
        "potential") {
      reader_.fail_expected("contact.law", expected(contact_fields, "law"), value.at("law"));
    }
    ContactLaw& law = scene.law;
    law.normal.kn = reader_.positive(value.at("kn"), "contact.kn", expected(contact_fields, "kn"));
    h(value.at("H"), scene);
    friction(value, law);
    if (value.contains("damping_ratio")) {
      law.damping_ratio = reader_.non_negative(value.at("damping_ratio"), "contact.damping_ratio",
                                               expected(contact_fields, "damping_ratio"));
    }
    if (value.contains("policy")) {
      law.policy = reader_.choice(value.at("policy"), "contact.policy",
                                  expected(contact_fields, "policy"), &kernel::parse_policy);
    }
    if (value.contains("demarcation")) {
      law.normal.demarcation =
          reader_.choice(value.at("demarcation"), "contact.demarcation",
                         expected(contact_fields, "demarcation"), &kernel::parse_demarcation);
    }
  }

  void blocks(const json& document, Scene& scene) const {
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

  // Each region cut by the joint sets (kernel::cut_region), appended to the blocks as
  // "<id_prefix>_<k>", k from 1 in the kernel's order.
  void regions(const json& document, Scene& scene) const {
    if (!document.contains("region")) {
      if (document.contains("joint_sets")) {
        reader_.fail("joint_sets", "joint sets cut a region; expected a \"region\" beside them");
      }
      return;
    }
    const std::vector<kernel::JointSet> sets = joint_sets(document);
    const json& value = document.at("region");
    scene.generated_first = scene.blocks.size();
    if (value.is_array()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        region(value[i], json_element("region", i), sets, scene);
      }
    } else {
      region(value, "region", sets, scene);
    }
    scene.generated_count = scene.blocks.size() - scene.generated_first;
  }

  void region(const json& value, const std::string& path, std::span<const kernel::JointSet> sets,
              Scene& scene) const {
    reader_.check_object(value, path, expected(scene_fields, "region"), region_fields);
    const std::vector<kernel::Point2> outline = reader_.polygon(
        value.at("vertices"), json_child(path, "vertices"), expected(region_fields, "vertices"));
    const Material material = material_of(value.at("material"), json_child(path, "material"));
    std::string group, prefix = "region";
    if (value.contains("group")) {
      group = reader_.string(value.at("group"), json_child(path, "group"),
                             expected(region_fields, "group"));
    }
    if (value.contains("id_prefix")) {
      prefix = reader_.string(value.at("id_prefix"), json_child(path, "id_prefix"),
                              expected(region_fields, "id_prefix"));
    }
    kernel::CutOptions options;
    if (value.contains("min_block_area")) {
      options.min_block_area =
          reader_.non_negative(value.at("min_block_area"), json_child(path, "min_block_area"),
                               expected(region_fields, "min_block_area"));
    }
    std::vector<std::vector<kernel::Point2>> pieces;
    try {
      pieces = kernel::cut_region(outline, sets, options);
    } catch (const kernel::InvalidCut& e) {
      const std::string field = cut_error_path(path, e);
      reader_.fail(field, field == path ? std::string(e.what()) : e.problem());
    }
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      BlockSpec spec;
      spec.id = prefix + "_" + std::to_string(k + 1);
      const bool taken = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                     [&](const BlockSpec& b) { return b.id == spec.id; });
      if (taken) {
        reader_.fail(json_child(path, "id_prefix"),
                     "the generated id \"" + spec.id +
                         "\" is also a block's; expected a prefix no other block id uses");
      }
      spec.material = material;
      spec.group = group;
      spec.vertices = std::move(pieces[k]);
      scene.blocks.push_back(std::move(spec));
      scene.material_names.push_back(value.at("material").get<std::string>());
    }
  }

  // Per pair of groups; what an interface leaves out comes from "contact".
  void interfaces(const json& document, Scene& scene) const {
    if (!document.contains("interfaces")) return;
    const json& value = document.at("interfaces");
    if (!value.is_array()) {
      reader_.fail_expected("interfaces", expected(scene_fields, "interfaces"), value);
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
      const std::string path = json_element("interfaces", i);
      Interface face = interface(value[i], path, scene.law);
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
    // An interface whose group no block has would never act: most likely a misspelt name.
    for (std::size_t i = 0; i < scene.law.interfaces.size(); ++i) {
      for (std::size_t g = 0; g < 2; ++g) {
        const std::string& group = scene.law.interfaces[i].groups[g];
        const bool used = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                      [&](const BlockSpec& b) { return b.group == group; });
        if (!used) {
          reader_.fail(json_element(json_child(json_element("interfaces", i), "between"), g),
                       "no block, region or boundary is in the group \"" + group +
                           "\"; expected the group of one of them");
        }
      }
    }
  }

  // Each segment becomes a fixed rectangle (a §3.3 virtual polygon) appended to the blocks: the
  // segment is its edge from -> to, and it extends `depth` to the right of that direction.
  void boundaries(const json& document, Scene& scene) const {
    if (!document.contains("boundaries")) return;
    const json& value = document.at("boundaries");
    if (!value.is_array()) {
      reader_.fail_expected("boundaries", expected(scene_fields, "boundaries"), value);
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
      const std::string path = json_element("boundaries", i);
      BlockSpec spec = boundary(value[i], path);
      const bool taken = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                     [&](const BlockSpec& b) { return b.id == spec.id; });
      if (taken) {
        reader_.fail(json_child(path, "id"), "duplicate id \"" + spec.id +
                                                 "\"; expected ids unique among blocks and boundaries");
      }
      scene.blocks.push_back(std::move(spec));
      scene.material_names.push_back(value[i].at("material").get<std::string>());
    }
  }

  // Without "output" or "output.track", every block that is not fixed is tracked.
  // Without "output" or "output.track", every block that is not fixed is tracked.
  void output(const json& document, Scene& scene) const {
    SceneOutput output = read_scene_output(reader_, document, scene.blocks);
    scene.track = std::move(output.track);
    scene.every = output.every;
  }

  void resolve_h(Scene& scene) const {
    switch (scene.h_rule) {
      case HRule::given:
        return;
      case HRule::mean_edge:
        scene.law.normal.H = mean_edge_length(scene.blocks);
        return;
      case HRule::mean_edge_movable: {
        std::vector<BlockSpec> movable;
        std::copy_if(scene.blocks.begin(), scene.blocks.end(), std::back_inserter(movable),
                     [](const BlockSpec& b) { return !b.fixed; });
        if (movable.empty()) {
          reader_.fail("contact.H", "\"mean_edge_movable\" needs a block that is not fixed");
        }
        scene.law.normal.H = mean_edge_length(movable);
        return;
      }
      case HRule::inscribed:
        scene.law.normal.H = smallest_inscribed_radius(scene.blocks);
        return;
    }
  }

 private:
  Material material(const json& value, const std::string& name) const {
    return read_material(reader_, value, json_child("materials", name));
  }

  void h(const json& value, Scene& scene) const {
    const std::string_view what = expected(contact_fields, "H");
    if (value.is_string()) {
      scene.h_rule = reader_.choice(value, "contact.H", what, &parse_h_rule);
      return;
    }
    scene.h_rule = HRule::given;
    scene.law.normal.H = reader_.positive(value, "contact.H", what);
  }

  void friction(const json& value, ContactLaw& law) const {
    const bool has_kt = value.contains("kt");
    const bool has_phi = value.contains("friction_angle_deg");
    if (!has_kt && !has_phi) {
      for (const std::string_view field : {"friction", "cohesion"}) {
        if (value.contains(field)) {
          reader_.fail(json_child("contact", field),
                       "a friction parameter of frictionless contact; give kt and "
                       "friction_angle_deg beside it, or leave it out");
        }
      }
      return;
    }
    if (has_kt != has_phi) {
      const std::string_view missing = has_kt ? "friction_angle_deg" : "kt";
      reader_.fail(json_child("contact", missing),
                   "missing field; expected " + std::string(expected(contact_fields, missing)) +
                       " (kt and friction_angle_deg come together; give neither for "
                       "frictionless contact)");
    }
    FrictionLaw friction;
    friction.kt = reader_.positive(value.at("kt"), "contact.kt", expected(contact_fields, "kt"));
    const std::string_view phi_expected = expected(contact_fields, "friction_angle_deg");
    friction.friction_angle_deg = reader_.non_negative(value.at("friction_angle_deg"),
                                                       "contact.friction_angle_deg", phi_expected);
    if (!(friction.friction_angle_deg < 90.0)) {
      reader_.fail_expected("contact.friction_angle_deg", phi_expected,
                            value.at("friction_angle_deg"));
    }
    if (value.contains("friction")) {
      friction.model = reader_.choice(value.at("friction"), "contact.friction",
                                      expected(contact_fields, "friction"),
                                      &contact::parse_friction_model);
    }
    if (value.contains("cohesion")) {
      friction.cohesion = reader_.non_negative(value.at("cohesion"), "contact.cohesion",
                                               expected(contact_fields, "cohesion"));
    }
    law.friction = friction;
  }

  BlockSpec block(const json& value, const std::string& path) const {
    reader_.check_object(
        value, path, "a block, an object {\"id\", \"material\", \"vertices\", ...}", block_fields);
    BlockSpec spec;
    spec.id = reader_.string(value.at("id"), json_child(path, "id"), expected(block_fields, "id"));
    if (spec.id.empty()) {
      reader_.fail_expected(json_child(path, "id"), expected(block_fields, "id"), value.at("id"));
    }
    spec.material = material_of(value.at("material"), json_child(path, "material"));
    spec.vertices = polygon(value.at("vertices"), json_child(path, "vertices"), spec.id);
    if (value.contains("fixed")) {
      spec.fixed = reader_.boolean(value.at("fixed"), json_child(path, "fixed"),
                                   expected(block_fields, "fixed"));
    }
    if (value.contains("rigid")) {
      spec.rigid = reader_.boolean(value.at("rigid"), json_child(path, "rigid"),
                                   expected(block_fields, "rigid"));
    }
    if (value.contains("group")) {
      spec.group = reader_.string(value.at("group"), json_child(path, "group"),
                                  expected(block_fields, "group"));
    }
    if (value.contains("velocity")) {
      const std::string velocity_path = json_child(path, "velocity");
      const auto v = reader_.numbers(value.at("velocity"), velocity_path, 3,
                                     expected(block_fields, "velocity"));
      if (spec.fixed && (v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0)) {
        reader_.fail(velocity_path,
                     "a fixed block does not move; expected no velocity (or zeros) on it");
      }
      spec.velocity = {v[0], v[1]};
      spec.omega = v[2];
    }
    return spec;
  }

  std::vector<kernel::JointSet> joint_sets(const json& document) const {
    std::vector<kernel::JointSet> sets;
    if (!document.contains("joint_sets")) return sets;
    const json& value = document.at("joint_sets");
    if (!value.is_array()) {
      reader_.fail_expected("joint_sets", expected(scene_fields, "joint_sets"), value);
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
      sets.push_back(joint_set(value[i], json_element("joint_sets", i)));
    }
    return sets;
  }

  kernel::JointSet joint_set(const json& item, const std::string& path) const {
    reader_.check_object(item, path, "a joint set {\"dip_deg\", \"spacing\", ...}", joint_set_fields);
    kernel::JointSet set;
    const std::string dip_path = json_child(path, "dip_deg");
    const std::string_view dip_expected = expected(joint_set_fields, "dip_deg");
    set.dip_deg = reader_.non_negative(item.at("dip_deg"), dip_path, dip_expected);
    if (!(set.dip_deg < 180.0)) reader_.fail_expected(dip_path, dip_expected, item.at("dip_deg"));
    set.spacing = reader_.positive(item.at("spacing"), json_child(path, "spacing"),
                                   expected(joint_set_fields, "spacing"));
    if (item.contains("offset")) {
      set.offset = reader_.number(item.at("offset"), json_child(path, "offset"),
                                  expected(joint_set_fields, "offset"));
    }
    if (item.contains("length")) {
      set.trace_length = reader_.positive(item.at("length"), json_child(path, "length"),
                                          expected(joint_set_fields, "length"));
    }
    if (item.contains("gap")) {
      if (!item.contains("length")) {
        reader_.fail(json_child(path, "gap"),
                     "a gap separates traces of finite length; expected \"length\" beside it");
      }
      set.gap = reader_.non_negative(item.at("gap"), json_child(path, "gap"),
                                     expected(joint_set_fields, "gap"));
    }
    return set;
  }

  Interface interface(const json& value, const std::string& path, const ContactLaw& law) const {
    reader_.check_object(value, path,
                         "an interface {\"between\", \"kn\", \"kt\", \"friction_angle_deg\", "
                         "\"cohesion\"}",
                         interface_fields);
    Interface face;
    const json& groups = value.at("between");
    if (!groups.is_array() || groups.size() != 2 || !groups[0].is_string() ||
        !groups[1].is_string()) {
      reader_.fail_expected(json_child(path, "between"), expected(interface_fields, "between"),
                            groups);
    }
    face.groups = {groups[0].get<std::string>(), groups[1].get<std::string>()};
    face.kn = value.contains("kn") ? reader_.positive(value.at("kn"), json_child(path, "kn"),
                                                      expected(interface_fields, "kn"))
                                   : law.normal.kn;
    face.friction = law.friction;
    if (!value.contains("kt") && !value.contains("friction_angle_deg") && !value.contains("cohesion")) {
      return face;
    }
    FrictionLaw friction = law.friction.value_or(FrictionLaw{});
    friction.kt = interface_value(value, path, "kt", law.friction.has_value(), friction.kt);
    friction.friction_angle_deg = interface_value(value, path, "friction_angle_deg",
                                                  law.friction.has_value(), friction.friction_angle_deg);
    if (!(friction.friction_angle_deg < 90.0)) {
      reader_.fail_expected(json_child(path, "friction_angle_deg"),
                            expected(interface_fields, "friction_angle_deg"),
                            value.at("friction_angle_deg"));
    }
    friction.cohesion = interface_value(value, path, "cohesion", law.friction.has_value(), friction.cohesion);
    face.friction = friction;
    return face;
  }

  // kt, friction_angle_deg or cohesion of an interface: its own (finite, >= 0; kt > 0), else the
  // scene's.
  double interface_value(const json& value, const std::string& path, std::string_view field,
                         bool has_default, double fallback) const {
    const std::string field_path = json_child(path, field);
    const std::string_view what = expected(interface_fields, field);
    if (!value.contains(field)) {
      if (!has_default) {
        reader_.fail(field_path, "missing field; expected " + std::string(what) +
                                     " (the scene's contact is frictionless: nothing to fall back on)");
      }
      return fallback;
    }
    return field == "kt" ? reader_.positive(value.at(field), field_path, what)
                         : reader_.non_negative(value.at(field), field_path, what);
  }

  BlockSpec boundary(const json& value, const std::string& path) const {
    reader_.check_object(value, path,
                         "a boundary segment, an object {\"id\", \"material\", \"from\", \"to\"}",
                         boundary_fields);
    BlockSpec spec;
    const std::string id_path = json_child(path, "id");
    spec.id = reader_.string(value.at("id"), id_path, expected(boundary_fields, "id"));
    if (spec.id.empty()) reader_.fail_expected(id_path, expected(boundary_fields, "id"), value.at("id"));
    spec.material = material_of(value.at("material"), json_child(path, "material"));
    spec.fixed = true;
    if (value.contains("group")) {
      spec.group = reader_.string(value.at("group"), json_child(path, "group"),
                                  expected(boundary_fields, "group"));
    }
    const auto from = reader_.numbers(value.at("from"), json_child(path, "from"), 2,
                                      expected(boundary_fields, "from"));
    const auto to = reader_.numbers(value.at("to"), json_child(path, "to"), 2,
                                    expected(boundary_fields, "to"));
    const double dx = to[0] - from[0], dy = to[1] - from[1];
    const double length = std::hypot(dx, dy);
    if (!(length > 0.0) || !std::isfinite(length)) {
      reader_.fail(json_child(path, "to"), "the segment has no direction (to equals from) or " +
                                               std::string("overflows; expected two distinct ends"));
    }
    double depth = length;
    if (value.contains("depth")) {
      depth = reader_.positive(value.at("depth"), json_child(path, "depth"),
                               expected(boundary_fields, "depth"));
    }
    // Right of from -> to: (dy, -dx) / length. CCW order: the far side first, then to, from.
    const double rx = depth * dy / length, ry = -depth * dx / length;
    spec.vertices = {{from[0] + rx, from[1] + ry}, {to[0] + rx, to[1] + ry}, {to[0], to[1]},
                     {from[0], from[1]}};
    try {
      kernel::ConvexPolygon::make("boundary '" + spec.id + "'", spec.vertices,
                                  kernel::VertexOrder::require_ccw);
    } catch (const kernel::InvalidPolygon& e) {
      reader_.fail(path, std::string(e.what()) + "; expected a depth that is not negligible " +
                             "against the coordinates");
    }
    return spec;
  }

  Material material_of(const json& value, const std::string& path) const {
    return find_material(reader_, value, path, expected(block_fields, "material"), materials_);
  }

  std::vector<kernel::Point2> polygon(const json& value, const std::string& path,
                                      const std::string& id) const {
    std::vector<kernel::Point2> vertices =
        reader_.polygon(value, path, expected(block_fields, "vertices"));
    try {
      kernel::ConvexPolygon::make("block '" + id + "'", vertices, kernel::VertexOrder::require_ccw);
    } catch (const kernel::InvalidPolygon& e) {
      if (e.reason() == kernel::InvalidPolygon::Reason::not_convex) {
        simple_non_convex(vertices, path, id);
        return vertices;
      }
      reader_.fail(
          e.vertex() >= 0 ? json_element(path, static_cast<std::size_t>(e.vertex())) : path,
          e.what());
    }
    return vertices;
  }

  // A non-convex block is allowed when it is simple and CCW (the engine partitions it).
  void simple_non_convex(const std::vector<kernel::Point2>& vertices, const std::string& path,
                         const std::string& id) const {
    try {
      kernel::convex_partition(vertices);
    } catch (const kernel::InvalidCut& e) {
      reader_.fail(path, "block '" + id + "' is not convex, and not a simple CCW polygon either (" +
                             e.what() + ")");
    }
  }

  JsonReader reader_;
  Materials materials_;
};

}  // namespace

std::string_view to_string(HRule rule) {
  switch (rule) {
    case HRule::given:
      return "given";
    case HRule::mean_edge:
      return "mean_edge";
    case HRule::mean_edge_movable:
      return "mean_edge_movable";
    case HRule::inscribed:
      return "inscribed";
  }
  return "?";
}

std::size_t step_count(const Scene& scene) { return step_count(scene.duration, scene.params.dt); }

std::size_t step_count(double duration, double dt) {
  const double ratio = duration / dt;
  const double nearest = std::round(ratio);
  const bool integral = std::abs(ratio - nearest) <= 1e-9 * nearest;
  return static_cast<std::size_t>(integral ? nearest : std::ceil(ratio));
}

double mean_edge_length(std::span<const BlockSpec> blocks) {
  double total = 0.0;
  std::size_t edges = 0;
  for (const BlockSpec& b : blocks) {
    const std::size_t n = b.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
      const kernel::Point2& p = b.vertices[i];
      const kernel::Point2& q = b.vertices[(i + 1) % n];
      total += std::hypot(q.x - p.x, q.y - p.y);
    }
    edges += n;
  }
  return total / static_cast<double>(edges);
}

double smallest_inscribed_radius(std::span<const BlockSpec> blocks) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const BlockSpec& b : blocks) {
    const std::vector<std::vector<kernel::Point2>> parts = kernel::convex_partition(b.vertices);
    double largest = 0.0;
    for (const auto& part : parts) largest = std::max(largest, kernel::inscribed_radius(part));
    smallest = std::min(smallest, largest);
  }
  return smallest;
}

std::uint64_t scene_digest(const json& document) {
  json physics = document;
  physics.erase("description");
  physics.erase("output");
  if (physics.contains("time") && physics["time"].is_object()) physics["time"].erase("duration");
  // FNV-1a over the compact text; nlohmann::json keeps members sorted by name, so the text, and
  // the digest, do not depend on the file's member order or spacing.
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : physics.dump()) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

Scene parse_scene(const json& document, const std::string& source_name) {
  SceneParser parser(source_name);
  const JsonReader reader(source_name);
  if (!document.is_object()) {
    reader.fail_expected("", "a JSON object {\"dimension\", \"time\", \"blocks\", ...}", document);
  }
  parser.format(document);
  parser.dimension(document);
  reader.check_object(document, "", "a scene object", scene_fields);
  Scene scene;
  scene.source = source_name;
  if (document.contains("description")) {
    scene.description = reader.string(document.at("description"), "description",
                                      expected(scene_fields, "description"));
  }
  parser.time(document.at("time"), scene);
  parser.physics(document, scene);
  parser.materials(document.at("materials"));
  parser.contact(document.at("contact"), scene);
  parser.blocks(document, scene);
  parser.regions(document, scene);
  if (scene.blocks.empty()) {
    reader.fail("blocks", "the scene has no blocks; expected \"blocks\" or a \"region\"");
  }
  parser.resolve_h(scene);  // from the blocks only: a boundary's depth is a construction aid
  parser.boundaries(document, scene);
  parser.interfaces(document, scene);
  parser.output(document, scene);
  scene.digest = scene_digest(document);
  return scene;
}

nlohmann::ordered_json generated_blocks_json(const Scene& scene) {
  nlohmann::ordered_json blocks = nlohmann::ordered_json::array();
  for (std::size_t i = scene.generated_first; i < scene.generated_first + scene.generated_count; ++i) {
    const BlockSpec& b = scene.blocks[i];
    nlohmann::ordered_json block;
    block["id"] = b.id;
    block["material"] = scene.material_names[i];
    if (!b.group.empty()) block["group"] = b.group;
    nlohmann::ordered_json vertices = nlohmann::ordered_json::array();
    for (const kernel::Point2& p : b.vertices) vertices.push_back({p.x, p.y});
    block["vertices"] = std::move(vertices);
    blocks.push_back(std::move(block));
  }
  return {{"blocks", std::move(blocks)}};
}

Scene read_scene_file(const std::filesystem::path& file) {
  return parse_scene(read_json_file(file), file.string());
}

std::vector<std::string> stiffness_warnings(const Scene& scene) {
  double e_min = std::numeric_limits<double>::infinity(), e_max = 0.0;
  for (const BlockSpec& b : scene.blocks) {
    if (b.fixed) continue;
    e_min = std::min(e_min, b.material.youngs_modulus);
    e_max = std::max(e_max, b.material.youngs_modulus);
  }
  std::vector<std::string> warnings;
  if (e_max == 0.0) return warnings;  // nothing moves
  const auto text = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", x);
    return std::string(buffer);
  };
  const auto check = [&](const std::string& where, double kn, const std::optional<FrictionLaw>& f) {
    if (kn < 1e-3 * e_min) {
      warnings.push_back(where + ".kn = " + text(kn) + " Pa is below a thousandth of the blocks' "
                         "Young's modulus (" + text(e_min) + " Pa): the blocks will sink deep into "
                         "each other; kn of E/10 to E is usual");
    }
    if (kn > 1e2 * e_max) {
      warnings.push_back(where + ".kn = " + text(kn) + " Pa is above 100 times the blocks' Young's "
                         "modulus (" + text(e_max) + " Pa): the critical time step shrinks with "
                         "sqrt(kn) for no gain in accuracy; kn of E/10 to E is usual");
    }
    if (!f) return;
    // A face-on-face contact of length H has the normal stiffness 2 kn H / H = 2 kn (N/m per m).
    const double normal = 2.0 * kn;
    if (f->kt < 1e-3 * normal || f->kt > 1e3 * normal) {
      warnings.push_back(where + ".kt = " + text(f->kt) + " N/m is more than 1000 times off the "
                         "normal stiffness of a face contact of length H, 2 kn = " + text(normal) +
                         " N/m (kn in Pa, kt in N/m per metre of thickness); kt of kn to 2 kn is "
                         "usual");
    }
  };
  check("contact", scene.law.normal.kn, scene.law.friction);
  for (std::size_t k = 0; k < scene.law.interfaces.size(); ++k) {
    const Interface& face = scene.law.interfaces[k];
    check("interfaces[" + std::to_string(k) + "]", face.kn, face.friction);
  }
  return warnings;
}

}  // namespace rockcontact::dynamics
