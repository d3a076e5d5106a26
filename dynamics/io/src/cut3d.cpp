#include "rockcontact/dynamics/io/cut3d.hpp"

#include <span>
#include <string_view>
#include <utility>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/moments.hpp"

namespace rockcontact::dynamics {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

constexpr JsonField document_fields[] = {
    {"dimension", true, "3"},
    {"region", true,
     "the region: {\"vertices\", \"faces\"}, {\"box\"} or {\"parts\"}, with \"material\", \"group\", "
     "\"id_prefix\", \"min_block_volume\""},
    {"joint_sets", false, "an array of joint sets {\"dip_deg\", \"dip_direction_deg\", \"spacing\", \"offset\"}"},
};
constexpr JsonField region_fields[] = {
    {"vertices", false, "the region's vertices, an array of [x, y, z] in m (with \"faces\")"},
    {"faces", false, "the region's faces, vertex loops counter-clockwise seen from outside (with \"vertices\")"},
    {"box", false, "an axis-aligned box {\"min\": [x, y, z], \"max\": [x, y, z]} in m"},
    {"parts", false, "the convex parts of a non-convex region, an array of {\"vertices\", \"faces\"}"},
    {"material", false, "the material of every block cut from it, a name"},
    {"group", false, "the group of those blocks, a string"},
    {"id_prefix", false, "their ids are <id_prefix>_1, <id_prefix>_2, ..., a string"},
    {"min_block_volume", false,
     "the volume in m³ below which a cut block is merged into a neighbour, a finite number >= 0, or \"auto\" "
     "(the default: 1e-3 of the region's volume per block of the cut)"},
};
constexpr JsonField box_fields[] = {
    {"min", true, "the lower corner [x, y, z] in m"},
    {"max", true, "the upper corner [x, y, z] in m, each coordinate above min's"},
};
constexpr JsonField joint_set_fields[] = {
    {"dip_deg", true, "the dip in degrees, a number in [0, 90]"},
    {"dip_direction_deg", true, "the dip direction in degrees clockwise from North, a number in [0, 360)"},
    {"spacing", true, "the spacing of the planes in m, a finite number > 0"},
    {"offset", false, "the offset of the planes along their normal in m, a finite number"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

PolyhedronSpec box(const JsonReader& reader, const json& value, const std::string& path) {
  reader.check_object(value, path, expected(region_fields, "box"), box_fields);
  const auto lo = reader.numbers(value.at("min"), json_child(path, "min"), 3, expected(box_fields, "min"));
  const auto hi = reader.numbers(value.at("max"), json_child(path, "max"), 3, expected(box_fields, "max"));
  if (!(lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2])) {
    reader.fail_expected(json_child(path, "max"), expected(box_fields, "max"), value.at("max"));
  }
  return {{{lo[0], lo[1], lo[2]}, {hi[0], lo[1], lo[2]}, {hi[0], hi[1], lo[2]}, {lo[0], hi[1], lo[2]},
           {lo[0], lo[1], hi[2]}, {hi[0], lo[1], hi[2]}, {hi[0], hi[1], hi[2]}, {lo[0], hi[1], hi[2]}},
          {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
}

void read_region(const JsonReader& reader, const json& value, Cut3Input& input) {
  const std::string path = "region";
  reader.check_object(value, path, expected(document_fields, "region"), region_fields);
  const int forms = (value.contains("vertices") || value.contains("faces") ? 1 : 0) + (value.contains("box") ? 1 : 0) +
                    (value.contains("parts") ? 1 : 0);
  if (forms != 1) {
    reader.fail(path, "expected exactly one of \"vertices\" with \"faces\", \"box\" or \"parts\"");
  }
  if (value.contains("box")) {
    input.region.push_back(box(reader, value.at("box"), json_child(path, "box")));
  } else if (value.contains("parts")) {
    const json& parts = value.at("parts");
    const std::string parts_path = json_child(path, "parts");
    if (!parts.is_array() || parts.empty()) reader.fail_expected(parts_path, expected(region_fields, "parts"), parts);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      input.region.push_back(reader.polyhedron(parts[i], json_element(parts_path, i), "a convex part {\"vertices\", \"faces\"}"));
    }
  } else {
    json solid = json::object();
    for (const char* key : {"vertices", "faces"}) {
      if (!value.contains(key)) reader.fail(path, std::string("expected \"") + key + "\" beside the other");
      solid[key] = value.at(key);
    }
    input.region.push_back(reader.polyhedron(solid, path, expected(document_fields, "region")));
  }
  for (auto [key, target] : {std::pair{"material", &input.material}, std::pair{"group", &input.group},
                             std::pair{"id_prefix", &input.id_prefix}}) {
    if (value.contains(key)) *target = reader.string(value.at(key), json_child(path, key), expected(region_fields, key));
  }
  if (value.contains("min_block_volume") && value.at("min_block_volume") != "auto") {
    input.min_block_volume = reader.non_negative(value.at("min_block_volume"), json_child(path, "min_block_volume"),
                                                 expected(region_fields, "min_block_volume"));
  }
}

kernel::JointSet3 read_joint_set(const JsonReader& reader, const json& item, const std::string& path) {
  reader.check_object(item, path, "a joint set {\"dip_deg\", \"dip_direction_deg\", \"spacing\", ...}", joint_set_fields);
  kernel::JointSet3 set;
  set.dip_deg = reader.non_negative(item.at("dip_deg"), json_child(path, "dip_deg"), expected(joint_set_fields, "dip_deg"));
  if (!(set.dip_deg <= 90)) reader.fail_expected(json_child(path, "dip_deg"), expected(joint_set_fields, "dip_deg"), item.at("dip_deg"));
  const std::string direction_path = json_child(path, "dip_direction_deg");
  set.dip_direction_deg = reader.non_negative(item.at("dip_direction_deg"), direction_path,
                                              expected(joint_set_fields, "dip_direction_deg"));
  if (!(set.dip_direction_deg < 360)) {
    reader.fail_expected(direction_path, expected(joint_set_fields, "dip_direction_deg"), item.at("dip_direction_deg"));
  }
  set.spacing = reader.positive(item.at("spacing"), json_child(path, "spacing"), expected(joint_set_fields, "spacing"));
  if (item.contains("offset")) {
    set.offset = reader.number(item.at("offset"), json_child(path, "offset"), expected(joint_set_fields, "offset"));
  }
  return set;
}

ordered_json solid_json(const kernel::ConvexPolyhedron& p) {
  ordered_json vertices = ordered_json::array(), faces = ordered_json::array();
  for (const auto& v : p.vertices()) vertices.push_back({v.x, v.y, v.z});
  for (const auto& f : p.input_faces()) faces.push_back(f);
  return {{"vertices", std::move(vertices)}, {"faces", std::move(faces)}};
}

}  // namespace

bool is_cut3_document(const json& document) {
  return document.is_object() && document.contains("dimension") && document.at("dimension") == 3;
}

Cut3Input parse_cut3(const json& document, const std::string& source_name) {
  const JsonReader reader(source_name);
  reader.check_object(document, "", "a JSON object {\"dimension\": 3, \"region\", \"joint_sets\"}", document_fields);
  if (document.at("dimension") != 3) reader.fail_expected("dimension", "3", document.at("dimension"));
  Cut3Input input;
  input.source = source_name;
  read_region(reader, document.at("region"), input);
  if (document.contains("joint_sets")) {
    const json& sets = document.at("joint_sets");
    if (!sets.is_array()) reader.fail_expected("joint_sets", expected(document_fields, "joint_sets"), sets);
    for (std::size_t i = 0; i < sets.size(); ++i) {
      input.joint_sets.push_back(read_joint_set(reader, sets[i], json_element("joint_sets", i)));
    }
  }
  return input;
}

Cut3Result cut3d(const Cut3Input& input) {
  std::vector<kernel::ConvexPolyhedron> parts;
  double region_volume = 0.0;
  for (std::size_t i = 0; i < input.region.size(); ++i) {
    const std::string name = input.region.size() == 1 ? "region" : "region.parts[" + std::to_string(i) + "]";
    try {
      parts.push_back(kernel::ConvexPolyhedron::make(name, input.region[i].vertices, input.region[i].faces));
    } catch (const kernel::InvalidPolyhedron& e) {
      throw InputError(input.source, name, e.what());
    }
    region_volume += kernel::moments(parts.back()).volume;
  }
  Cut3Result cut;
  try {
    // Cut unmerged first: "auto" needs the number of blocks the cut makes.
    cut.blocks = kernel::cut_region<kernel::Filtered>(parts, input.joint_sets, input.id_prefix);
  } catch (const kernel::InvalidCut& e) {
    throw InputError(input.source, e.subject(), e.problem());
  }
  const std::size_t unmerged = cut.blocks.size();
  cut.min_block_volume = input.min_block_volume.value_or(auto_min_block_volume_fraction * region_volume /
                                                         static_cast<double>(unmerged));
  cut.blocks = kernel::merge_small_blocks(std::move(cut.blocks), {cut.min_block_volume}, input.id_prefix);
  cut.merged = unmerged - cut.blocks.size();
  return cut;
}

ordered_json cut3d_blocks(const Cut3Input& input, const Cut3Result& cut) {
  const std::vector<kernel::CutBlock3>& blocks = cut.blocks;
  ordered_json out = ordered_json::array();
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    ordered_json block;
    block["id"] = input.id_prefix + "_" + std::to_string(b + 1);
    if (!input.material.empty()) block["material"] = input.material;
    if (!input.group.empty()) block["group"] = input.group;
    if (blocks[b].parts.size() == 1) {
      ordered_json solid = solid_json(blocks[b].parts[0]);
      block["vertices"] = std::move(solid["vertices"]);
      block["faces"] = std::move(solid["faces"]);
    } else {
      ordered_json solids = ordered_json::array();
      for (const auto& part : blocks[b].parts) solids.push_back(solid_json(part));
      block["parts"] = std::move(solids);
    }
    out.push_back(std::move(block));
  }
  return {{"blocks", std::move(out)}};
}

}  // namespace rockcontact::dynamics
