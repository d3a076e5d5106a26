#pragma once
// 3D scenes: the JSON documents with "dimension": 3 that `rockcontact run` reads, mapped onto the
// implicit 3D DDA (dda3d.hpp). Read with the 2D scene's machinery (json_read.hpp): every field is
// checked, unknown fields are errors naming the file and the JSON path.
//
//   {"format": "rockcontact-scene/1"                 (optional, as in 2D)
//    "description": text                              (optional, ignored by the run)
//    "dimension": 3,
//    "time": {"dt": s > 0 (the largest step), "duration": s > 0,
//             "max_displacement_ratio": 0 < r < 1 (optional, default 0.001: a step is cut when
//                                        a vertex would move more than r times the diagonal
//                                        of the scene's bounding box),
//             "max_rotation_deg": 0 < θ < 90 (optional, default 1: a step is cut when a block
//                                  would turn by more than θ degrees, seed 001 §5.2)},
//    "gravity": [gx, gy, gz] m/s²                     (optional, default [0, 0, -9.81])
//    "materials": {name: {"density": kg/m³ > 0, "youngs_modulus": Pa > 0,
//                         "poisson_ratio": -1 < nu < 0.5}, ...},
//    "contact": {"law": "penalty",
//                "kn": N/m > 0 | "auto"   (per constraint; optional, default "auto":
//                                          auto_normal_penalty3d of the blocks, dda3d.hpp)
//                "kt": N/m > 0 | "auto"   (per constraint; optional, default "auto": kn / 10)
//                "friction_angle_deg": [0, 90)   (optional, default 0: frictionless)
//                "cohesion": Pa >= 0             (optional, default 0)
//                "tensile_strength": Pa >= 0     (optional, default 0)
//                "policy": "float" | "filtered" | "exact" | "checked"  (optional, default
//                                                                         filtered)},
//    "interfaces": [{"between": [group, group], "friction_angle_deg": [0, 90),
//                    "cohesion": Pa >= 0, "tensile_strength": Pa >= 0}, ...]
//                                                     (optional; what an interface leaves out
//                                                      comes from "contact"; one per pair of
//                                                      groups, each group some block's)
//    "blocks": [{"id": unique string, "material": a name of "materials",
//                "vertices": [[x, y, z], ...] m, "faces": [[i, j, k, ...], ...]
//                                 (a convex polyhedron, faces counter-clockwise seen from
//                                  outside; kernel/3d/convex_polyhedron.hpp)
//                | "parts": [{"vertices", "faces"}, ...]   (convex parts of one body),
//                "group": a name interfaces refer to (default ""),
//                "fixed": bool (default false), "rigid": bool (default false: 12 unknowns,
//                                                    strains included; true: 6),
//                "velocity": [vx, vy, vz, wx, wy, wz] m/s, rad/s of the centroid (default 0;
//                            not allowed on a fixed block)}, ...]
//                                                     (optional when "region" is given)
//    "region": the region of `rockcontact cut` in 3D (cut3d.hpp): {"vertices", "faces"} |
//              {"box": {"min", "max"}} | {"parts": [...]}, with "material" (required here),
//              "group", "id_prefix" (default "region"), "min_block_volume" (m³ >= 0 or
//              "auto", the default: 1e-3 of the region's volume per block of the cut; blocks
//              below it merged into a neighbour)       (optional; blocks
//                                                        "<id_prefix>_<k>", movable)
//    "joint_sets": [{"dip_deg": [0, 90], "dip_direction_deg": [0, 360) clockwise from North,
//                    "spacing": m > 0, "offset": m (default 0)}, ...]   (optional, with
//                                                                        "region")
//    "output": {"track": [block ids] (default: every block that is not fixed),
//               "every": steps >= 1 (default 100)}}                          (optional)
//
// Axes x East, y North, z Up. Polyhedra are validated here (kernel::ConvexPolyhedron::make) so
// that a bad face or vertex is reported with the file and the path "blocks[i].faces[f]" or
// "blocks[i].vertices[k]" ("blocks[i].parts[j]...." for a part), the kernel's message naming
// the block id, the face and the vertex.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/dda3d.hpp"

namespace rockcontact::dynamics {

struct Scene3d {
  std::string source;       // the file it came from, for messages and the summary
  std::string description;  // free text, may be empty
  std::vector<Block3dSpec> blocks;          // explicit blocks, then those cut from the region
  std::vector<std::string> material_names;  // of each block, by index
  std::size_t generated_first = 0;          // the blocks cut from the region:
  std::size_t generated_count = 0;          // blocks[generated_first, + generated_count)
  double min_block_volume = 0.0;            // m³: the cut merged the region's blocks below this
  std::size_t merged_fragments = 0;         // so many of them, each into a neighbour
  ContactLaw3d law;
  bool kn_auto = false;  // law.kn is auto_normal_penalty3d's ("kn": "auto" or none)
  bool kt_auto = false;  // law.kt is law.kn / 10 ("kt": "auto" or none)
  Dda3dParams params;  // dt, gravity, max_displacement_ratio, max_rotation_deg from the scene; the rest default
  double duration = 0.0;           // s
  std::vector<std::string> track;  // ids of the tracked blocks, in the file's order
  std::size_t every = 100;         // record every `every` accepted steps
};

// Does the document say "dimension": 3 (a 3D scene, for parse_scene3d)?
bool is_scene3d_document(const nlohmann::json& document);

// Throws InputError ("<source>: <path>: ...") for anything the format above does not allow.
Scene3d parse_scene3d(const nlohmann::json& document, const std::string& source_name);

// Reads and parses a file; InputError also for an unreadable file or malformed JSON.
Scene3d read_scene3d_file(const std::filesystem::path& file);

}  // namespace rockcontact::dynamics
