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
//            plus, in each form, "material" (a name, optional), "group" (optional),
//            "id_prefix" (default "region") and "min_block_volume" (m³ >= 0 or "auto", the
//            default: the blocks below it are merged into the neighbour they share the largest
//            face with, kernel::merge_small_blocks; "auto" is 1e-3 of the region's volume per
//            block of the cut before merging, 0 merges nothing),
//    "joint_sets": [{"dip_deg": [0, 90], "dip_direction_deg": [0, 360) clockwise from North,
//                    "spacing": m > 0, "offset": m (default 0)}, ...]}
// Axes x East, y North, z Up; a set's planes are n . p = offset + k spacing with n its upward
// unit normal (block_cutting.hpp).
//
// Output: {"blocks": [{"id": "<id_prefix>_<k>", "material"?, "group"?, "vertices", "faces"}
//                    | {"id", "material"?, "group"?, "parts": [{"vertices", "faces"}, ...]}]}
// the block format of 3D scenes, vertices rounded to doubles (written exactly), faces
// counter-clockwise seen from outside.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
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
  std::optional<double> min_block_volume;  // m³ >= 0; empty for "auto"
  std::vector<kernel::JointSet3> joint_sets;
};

// "auto"'s min_block_volume: this fraction of the region's volume per block of the cut before
// merging. The slivers a cut leaves beside blocks of ordinary size are thousands of times
// smaller than the mean block: in the jointed mass example (examples/scenes3d), 3.3e-5 and
// 9.8e-5 m³ beside a mean of 0.98 m³ and a median of 0.54 m³. A thousandth of the mean takes
// those two there; the next block, 9.9e-4 m³, is only 1.1 % above it, and the smallest blocks
// form a continuum from there on (1.5e-3, 1.9e-3, 2.2e-3 m³, ...), so no fraction separates
// fragments from blocks in general: this one takes what is far below the mean.
inline constexpr double auto_min_block_volume_fraction = 1e-3;

struct Cut3Result {
  std::vector<kernel::CutBlock3> blocks;  // numbered from 1 in this order
  double min_block_volume = 0.0;          // m³: the bound the blocks were merged below ("auto"'s value)
  std::size_t merged = 0;                 // the fragments merged into a neighbour
};

// Does the document ask for the 3D cut ("dimension": 3)?
bool is_cut3_document(const nlohmann::json& document);

// Throws InputError naming `source_name`, the field path and what was expected.
Cut3Input parse_cut3(const nlohmann::json& document, const std::string& source_name);

// The blocks cut from the region, numbered from 1 (kernel::cut_region), those below
// min_block_volume merged (kernel::merge_small_blocks). Throws InputError naming "region" (a
// part that is not a valid convex polyhedron) or the joint set field (kernel::InvalidCut).
Cut3Result cut3d(const Cut3Input& input);

// The blocks of a cut of `input` as the output document above.
nlohmann::ordered_json cut3d_blocks(const Cut3Input& input, const Cut3Result& cut);

}  // namespace rockcontact::dynamics
