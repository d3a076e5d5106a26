#pragma once
// Scenes: the JSON documents `rockcontact run` reads, mapped onto the explicit 2D DDA
// (dda2d.hpp). Every field is checked; unknown fields are errors naming the file and JSON path.
//
//   {"format": "rockcontact-scene/1"                     (optional; another version is an
//                                                          error naming the one it needs)
//    "description": text                                  (optional, ignored by the run)
//    "dimension": 2                                       (3: a 3D scene, scene3d.hpp)
//    "time": {"dt": s > 0, "duration": s > 0},            (duration / dt at most 1e12 steps)
//    "gravity": [gx, gy] m/s²                             (optional, default [0, -9.81])
//    "plane": "stress" | "strain"                         (optional, default stress)
//    "damping": alpha 1/s >= 0                            (optional, default 0: eq. 5c off)
//    "analysis": "dynamic" | "static"                     (optional, default dynamic; static:
//                                                          relax to equilibrium, dda2d.hpp)
//    "static_tolerance": 0 < R < 1                        (optional, default 1e-6: the static
//                                                          run stops below this out-of-balance
//                                                          force ratio)
//    "initial_equilibrium": "auto" | true | false         (optional, default "auto": the
//                                                          blocks resting at the start are
//                                                          settled first, those without a
//                                                          static state start as given; true
//                                                          refuses them; dda2d.hpp)
//    "materials": {name: {"density": kg/m³ > 0, "youngs_modulus": Pa > 0,
//                         "poisson_ratio": -1 < nu < 0.5}, ...},
//    "contact": {"law": "potential", "kn": Pa > 0,
//                "H": m > 0 | "mean_edge" | "mean_edge_movable" | "inscribed",
//                "kt": N/m > 0, "friction_angle_deg": 0 <= phi < 90   (both or neither;
//                                                                       neither: frictionless)
//                "friction": "elastoplastic" | "paper"  (optional, default elastoplastic;
//                                                        contact/friction.hpp)
//                "cohesion": Pa >= 0                    (optional, default 0)
//                "damping_ratio": zeta >= 0             (optional, default 0: no contact
//                                                        dashpots; dda2d.hpp)
//                "policy": "float" | "filtered" | "exact" | "checked"  (optional, default filtered)
//                "demarcation": "paper" | "exact"},                (optional, default exact)
//    "blocks": [{"id": unique string, "material": a name of "materials",
//                "vertices": [[x, y], ...] m, CCW, simple, no collinear vertex (a
//                            non-convex block is split into convex parts by the engine),
//                "group": a name interfaces refer to (default ""),
//                "fixed": bool (default false), "rigid": bool (default false),
//                "velocity": [vx, vy, omega] m/s, m/s, rad/s of the centroid (default 0;
//                            not allowed on a fixed block)}, ...],
//                                                         (optional when "region" is given)
//    "region": {"vertices": [[x, y], ...] m, CCW, simple, "material": a name,
//               "group": a name (default ""), "id_prefix": text (default "region"),
//               "min_block_area": m² >= 0 (default 0: cut fragments below it are merged
//                                 into a neighbour, kernel::CutOptions)}
//              or an array of such regions                (optional; blocks "<id_prefix>_<k>")
//    "joint_sets": [{"dip_deg": [0, 180) degrees from +x, CCW, "spacing": m > 0,
//                    "offset": m (default 0), "length": m > 0 (default persistent),
//                    "gap": m >= 0 (with length)}, ...]    (optional, with "region";
//                                                          kernel/block_cutting.hpp)
//    "interfaces": [{"between": [group, group], "kn": Pa > 0, "kt": N/m > 0,
//                    "friction_angle_deg": [0, 90), "cohesion": Pa >= 0}, ...]
//                                                         (optional; what an interface leaves
//                                                          out comes from "contact", the
//                                                          friction law always does)
//    "boundaries": [{"id": unique among blocks and boundaries, "material": a name,
//                    "from": [x, y] m, "to": [x, y] m, "depth": m > 0 (default |to - from|),
//                    "group": a name (default "")},
//                   ...]                                  (optional; seed 000 §3.3)
//    "output": {"track": [block ids] (default: every block that is not fixed),
//               "every": steps >= 1 (default 100)}}                (optional)
//
// A boundary segment is, as in seed 000 §3.3, part of a virtual polygon: the fixed rectangle
// whose edge from -> to is the segment and which extends `depth` to its right (the free side is
// on the left, as for the edges of a CCW polygon: a floor runs from left to right). It is
// appended to the blocks as a fixed block with the boundary's id. Inside that rectangle the
// potential near the segment is the depth below it as long as a block penetrates less than
// depth / 2 and stays off the segment's ends; give a block instead where the shape matters.
//
// H, the potential's length scale (seed 000 eq. 14), is one number for the whole scene:
//   number       as given;
//   "mean_edge"  the mean edge length over every edge of every block (fixed ones included,
//                boundary segments not: their rectangles' depth is a construction aid): a
//                unified H in the sense of §5.1, the same for every pair (the paper's own
//                unified value there is the average of the longest and shortest edge);
//   "mean_edge_movable"  the same over the blocks that are not fixed: the contact stiffness then
//                does not depend on how large a fixed base or slope is drawn (with "mean_edge",
//                a 0.5 m block on a large drawn slope got H = 3.55 m);
//   "inscribed"  the paper's "previous approach" (§5.1) used each block's inscribed-circle
//                radius as its own H. Our contact law takes one H per scene, so this is the
//                smallest inscribed radius over all blocks (fixed ones included, boundary
//                segments not): the stiffest of the per-block potentials, the one that sets
//                the stability limit. A non-convex block counts with the largest inscribed
//                radius of its convex parts (a lower bound of its own).
//
// Polygons are validated here (kernel::ConvexPolygon) so that a bad vertex is reported with the
// file and the path "blocks[i].vertices[k]", the kernel's message naming the block id.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/dynamics/dda2d.hpp"

namespace rockcontact::dynamics {

enum class HRule { given, mean_edge, mean_edge_movable, inscribed };

std::string_view to_string(HRule rule);

struct Scene {
  std::string source;       // the file it came from, for messages and the summary
  std::string description;  // free text, may be empty
  // Explicit blocks, then the blocks cut from the region, then the boundary segments' polygons.
  std::vector<BlockSpec> blocks;
  std::vector<std::string> material_names;  // of each block, by index
  std::size_t generated_first = 0;          // the blocks cut from the region:
  std::size_t generated_count = 0;          // blocks[generated_first, + generated_count)
  ContactLaw law;  // law.normal.H already resolved from h_rule
  DdaParams params;
  double duration = 0.0;  // s
  HRule h_rule = HRule::given;
  std::vector<std::string> track;  // ids of the tracked blocks, in the file's order
  std::size_t every = 100;         // record tracks and frames every `every` steps
  double static_tolerance = 1.0e-6;  // static analysis: stop below this out-of-balance ratio
  std::uint64_t digest = 0;          // scene_digest of the document it was parsed from
};

// A 64-bit digest (FNV-1a) of what a scene's run depends on: the document without
// "description", "output" and "time.duration", so that a checkpoint still fits a scene whose
// run was lengthened or is recorded differently. Member order and spacing do not matter.
std::uint64_t scene_digest(const nlohmann::json& document);

// The number of steps that covers the duration: duration / dt rounded up, except that a ratio
// within 1e-9 (relative) of an integer counts as that integer (1.0 / 1e-4 is 10000 steps, not
// 10001 because of the decimal's rounding). The run ends at steps * dt >= duration.
std::size_t step_count(const Scene& scene);

// The same rule for a `duration` covered by steps of `dt` (s), shared by every scene format.
std::size_t step_count(double duration, double dt);

// Mean length of all edges of all blocks, m.
double mean_edge_length(std::span<const BlockSpec> blocks);

// min over blocks of the largest kernel::inscribed_radius of their convex parts, m.
double smallest_inscribed_radius(std::span<const BlockSpec> blocks);

// Throws InputError ("<source>: <path>: ...") for anything the format above does not allow.
Scene parse_scene(const nlohmann::json& document, const std::string& source_name);

// {"blocks": [...]} with the blocks cut from the scene's region, in the scene format
// ("id", "material", "group" when not empty, "vertices" with every double round-tripping), so
// they can be inspected, edited and pasted into a scene's "blocks".
nlohmann::ordered_json generated_blocks_json(const Scene& scene);

// Stiffnesses a scene accepts but a user most likely did not mean, one sentence each naming the
// field: kn below E/1000 or above 100 E of the movable blocks (Young's modulus), kt more than
// 1000 times off 2 kn, the normal stiffness of a face contact of length H (kn is in Pa, kt in
// N/m per metre of thickness). `rockcontact run` prints them as warnings.
std::vector<std::string> stiffness_warnings(const Scene& scene);

// Reads and parses a file; InputError also for an unreadable file or malformed JSON.
Scene read_scene_file(const std::filesystem::path& file);

}  // namespace rockcontact::dynamics
