#pragma once
// The 3D input of `rockcontact cut`: a region cut by persistent joint sets into blocks
// (kernel/3d/block_cutting.hpp), written as 3D scene blocks.
//
// Input (every field checked; unknown fields are errors):
//   {"dimension": 3,
//    "region": {"vertices": [[x, y, z], ...], "faces": [[i, j, k, ...], ...]}   a convex polyhedron
//            | {"box": {"min": [x, y, z], "max": [x, y, z]}}                   an axis-aligned box
//            | {"parts": [{"vertices", "faces"}, ...]}                          a non-convex region
//                                                                               as convex parts
//            plus, in each form, "material" (a name, optional), "group" (optional) and
//            "id_prefix" (default "region"),
//    "joint_sets": [{"dip_deg": [0, 90], "dip_direction_deg": [0, 360) clockwise from North,
//                    "spacing": m > 0, "offset": m (default 0)}, ...]}
// Axes x East, y North, z Up; a set's planes are n . p = offset + k spacing with n its upward
// unit normal (block_cutting.hpp).
//
// Output: {"blocks": [{"id": "<id_prefix>_<k>", "material"?, "group"?, "vertices", "faces"}
//                    | {"id", "material"?, "group"?, "parts": [{"vertices", "faces"}, ...]}]}
// the block format of 3D scenes, vertices rounded to doubles (written exactly), faces
// counter-clockwise seen from outside.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/kernel/3d/block_cutting.hpp"

namespace rockcontact::dynamics {

struct Cut3Input {
  std::string source;
  std::vector<PolyhedronSpec> region;  // convex parts, as given (validated by cut3d_blocks)
  std::string material;                // "" when not given
  std::string group;
  std::string id_prefix = "region";
  std::vector<kernel::JointSet3> joint_sets;
};

// Does the document ask for the 3D cut ("dimension": 3)?
bool is_cut3_document(const nlohmann::json& document);

// Throws InputError naming `source_name`, the field path and what was expected.
Cut3Input parse_cut3(const nlohmann::json& document, const std::string& source_name);

// The blocks cut from the region, numbered from 1 (kernel::cut_region). Throws InputError
// naming "region" (a part that is not a valid convex polyhedron) or the joint set field
// (kernel::InvalidCut).
std::vector<kernel::CutBlock3> cut3d(const Cut3Input& input);

// The blocks of cut3d as the output document above; throws what cut3d throws.
nlohmann::ordered_json cut3d_blocks(const Cut3Input& input);

}  // namespace rockcontact::dynamics
