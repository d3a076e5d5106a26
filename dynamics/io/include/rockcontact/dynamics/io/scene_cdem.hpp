#pragma once
// CDEM scenes: the JSON documents with "solver": "cdem" that `rockcontact run` reads, mapped onto
// the CDEM engine (cdem.hpp: deformable blocks meshed into triangles, explicit dynamics,
// two-scale clone-node or penalty contact). Read with the other scenes' machinery
// (json_read.hpp): every field is checked, unknown fields are errors naming the file and the
// JSON path.
//
//   {"format": "rockcontact-scene/1"                 (optional, as in the other scenes)
//    "description": text                              (optional, ignored by the run)
//    "dimension": 2                                   (optional; 2 if present)
//    "solver": "cdem",
//    "time": {"dt": s > 0, "duration": s > 0},        (duration / dt at most 1e12 steps; the
//                                                      run takes step_count(scene) steps)
//    "gravity": [gx, gy] m/s²                         (optional, default [0, -9.81])
//    "plane": "strain" | "stress"                     (optional, default strain)
//    "thickness": m > 0                               (optional, default 1: out of plane)
//    "damping": 1/s >= 0                              (optional, default 0: mass-proportional,
//                                                      C = damping M)
//    "materials": {name: {"density": kg/m³ > 0, "youngs_modulus": Pa > 0,
//                         "poisson_ratio": -1 < nu < 0.5}, ...}       (at least one)
//    "contact": {"law": "two-scale" | "penalty",
//                "search_tolerance": m > 0        (node-edge pairs closer than this are watched)
//                "friction_angle_deg": [0, 90)   (optional, default 0: frictionless)
//                "cohesion": Pa >= 0             (optional, default 0)
//                "tensile_strength": Pa >= 0     (optional, default 0)
//                "kn": N/m > 0 per node          (penalty: required; two-scale: not allowed)
//                "kt": N/m > 0 per node          (penalty only; optional, default kn)
//                "subdivide": bool               (two-scale only; optional, default false:
//                                                 subdivided elements at the clone nodes,
//                                                 seed 003 §5; see cdem.hpp for their cost)
//                "policy": "float" | "filtered" | "exact" | "checked"  (optional, default
//                                                 filtered: of the touch-time predicates)},
//    "blocks": [{"id": unique non-empty string, "material": a name of "materials",
//                "vertices": [[x, y], ...] m, at least 3 (a simple polygon, counter-clockwise,
//                            no repeated vertex: checked by the engine's mesher),
//                "mesh": {"max_edge": m > 0}     (required: the longest element edge),
//                "fixed": bool (default false: every node held at rest when true),
//                "velocity": [vx, vy, omega] m/s, m/s, rad/s of the mass centre (default 0;
//                            not allowed on a fixed block)}, ...]        (at least one)
//    "output": {"track": [block ids] (default: every block that is not fixed),
//               "every": steps >= 1 (default 100)}}                          (optional)
//
// What this reader leaves to the engine: the polygons themselves (orientation, simplicity,
// repeated vertices) and dt against the meshes' critical step. The Cdem constructor refuses them
// with std::invalid_argument naming the block or the parameter; `rockcontact run` reports that
// as bad input, prefixed with the scene's file name.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/cdem.hpp"

namespace rockcontact::dynamics {

struct SceneCdem {
  std::string source;       // the file it came from, for messages and the summary
  std::string description;  // free text, may be empty
  std::vector<CdemBlockSpec> blocks;  // in the file's order
  CdemParams params;                  // every field from the scene (or its default above)
  double duration = 0.0;              // s
  std::vector<std::string> track;     // ids of the tracked blocks, in the file's order
  std::size_t every = 100;            // record every `every` steps
};

// Does the document say "solver": "cdem" (a CDEM scene, for parse_scene_cdem)?
bool is_scene_cdem_document(const nlohmann::json& document);

// Throws InputError ("<source>: <path>: ...") for anything the format above does not allow.
SceneCdem parse_scene_cdem(const nlohmann::json& document, const std::string& source);

// Reads and parses a file; InputError also for an unreadable file or malformed JSON.
SceneCdem read_scene_cdem_file(const std::filesystem::path& file);

// The number of steps of the run, as in the 2D scenes (scene.hpp): duration / dt rounded up,
// except that a ratio within 1e-9 (relative) of an integer counts as that integer (0.3 / 0.1 is
// 3 steps, not 4 because of the decimals' rounding). The run ends at steps * dt >= duration.
std::size_t step_count(const SceneCdem& scene);

}  // namespace rockcontact::dynamics
