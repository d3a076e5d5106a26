#pragma once
// Pair-level check from JSON: the documents read and written by `rockcontact pairs`.
//
// Input in 2D (every field checked; unknown fields are errors, at the top level and in each pair):
//   {"dimension": 2 (optional), "kn": Pa > 0, "H": m > 0,
//    "policy": "float" | "filtered" | "exact" | "checked"  (optional, default filtered),
//    "demarcation": "paper" | "exact"              (optional, default exact),
//    "pairs": [{"id": unique string, "cp": [[x, y], ...], "tp": [[x, y], ...]}, ...]}
//
// Output (one result per pair, in input order; keys in this order):
//   {"policy", "demarcation",
//    "results": [{"id", "status": "separate" | "touch" | "overlap",
//                 "ip": [[x, y], ...] m, CCW, empty unless overlap,
//                 "area": m², "force": [fx, fy] normal force on CP in N/m (zero unless overlap),
//                 "point": [x, y] m, null unless overlap with a non-zero force,
//                 "fallbacks": exact re-evaluations spent on this pair}
//              | {"id", "status": "error", "error": message naming the polygon and vertex}],
//    "stats": {"pairs", "predicates", "fallbacks", "seconds"}}
//
// Input in 3D (the same rules):
//   {"dimension": 3, "kn": N/m per constraint > 0,
//    "tolerance": m >= 0 (optional, default 0: constraints for touching and overlapping pairs),
//    "policy": as in 2D (optional),
//    "pairs": [{"id", "cp": {"vertices": [[x, y, z], ...], "faces": [[i, j, k, ...], ...]},
//               "tp": {...}}, ...]}
// with faces counter-clockwise seen from outside (kernel/3d/convex_polyhedron.hpp).
//
// Output in 3D (one result per pair, in input order; keys in this order):
//   {"policy",
//    "results": [{"id", "status": "separate" | "touch" | "overlap",
//                 "volume": m³ of the intersection, 0 unless overlap,
//                 "distance": m, null unless separate,
//                 "penetration": {"depth": m, "normal": [nx, ny, nz]} or null unless overlap
//                                (translating tp by depth * normal makes the pair touch),
//                 "contact_set": {"dimension": 0 | 1 | 2, "vertices": [[x, y, z], ...]} or null
//                                unless touch (the set's corners, in any order),
//                 "constraints": [{"type": "vertex-face" | "edge-edge" | "vertex-edge" |
//                                  "vertex-vertex", "point_cp", "point_tp", "normal", "gap": m,
//                                  "force": [fx, fy, fz] N on tp}, ...]
//                                (listed when the pair touches, overlaps or is closer than
//                                tolerance; normal unit, from cp towards tp; gap
//                                (point_tp - point_cp) . normal, negative = penetration;
//                                force kn max(0, -gap) normal, its opposite acting on cp),
//                 "fallbacks"}
//              | {"id", "status": "error", "error": message naming the block, face and vertex}],
//    "stats": {"pairs", "predicates", "fallbacks", "seconds"}}
//
// Two kinds of bad input, kept apart on purpose: a document that does not have the shape above
// is an InputError (nothing is computed); a well-formed pair whose polygon is not a valid
// strictly convex CCW polygon (kernel::InvalidPolygon) or not a valid convex polyhedron
// (kernel::InvalidPolyhedron) is reported in that pair's result and the other pairs are still
// computed. Clockwise polygons are errors, not silently reversed.
//
// Doubles are written by nlohmann-json's shortest round-trip formatting, so reading the output
// back gives the computed doubles bit for bit.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics {

// A malformed input document. The message reads "<source>: <path>: <problem>", the problem
// saying what was expected and what was found.
class InputError : public std::runtime_error {
 public:
  // `path` is the JSON path of the offending field ("pairs[1].tp[2]"); empty for the document
  // as a whole (unreadable file, JSON syntax error).
  InputError(std::string source, std::string path, const std::string& problem);

  const std::string& source() const noexcept { return source_; }
  const std::string& path() const noexcept { return path_; }

 private:
  std::string source_;
  std::string path_;
};

// A convex polyhedron as given: vertices (m) and faces, vertex loops counter-clockwise seen
// from outside (validated when run).
struct PolyhedronSpec {
  std::vector<kernel::Point3> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
};

struct PairSpec {
  std::string id;
  std::vector<kernel::Point2> cp;  // contact polygon, m, as given (validated when run)
  std::vector<kernel::Point2> tp;  // target polygon, m, as given (validated when run)
};

struct Pair3Spec {
  std::string id;
  PolyhedronSpec cp;  // the block the constraints' normals point away from
  PolyhedronSpec tp;  // the block the penalty force of a constraint acts on
};

struct PairsInput {
  std::string source;  // where the document came from (file name), for messages
  int dimension = 2;   // 2: polygon pairs (`pairs`), 3: polyhedron pairs (`pairs3`)
  double kn = 0.0;     // normal penalty: Pa in 2D, N/m per constraint in 3D (> 0, finite)
  double H = 0.0;      // 2D: potential length scale, m (> 0, finite)
  double tolerance = 0.0;  // 3D: constraints are listed for pairs closer than this, m (>= 0)
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
  kernel::Demarcation demarcation = kernel::Demarcation::exact;
  std::vector<PairSpec> pairs;
  std::vector<Pair3Spec> pairs3;
};

// Choices made outside the document (command-line flags); when set they win over the file's.
struct PairsOverrides {
  std::optional<kernel::PolicyKind> policy;
  std::optional<kernel::Demarcation> demarcation;
};

// Throws InputError naming `source_name`, the field path and what was expected.
PairsInput parse_pairs(const nlohmann::json& document, const std::string& source_name);

// Reads and parses a file. Throws InputError for an unreadable file, malformed JSON (with the
// line and column reported by the JSON parser) or a document parse_pairs rejects.
PairsInput read_pairs_file(const std::filesystem::path& file);

// Evaluates every pair with contact::evaluate_pair under the effective policy and demarcation,
// reusing one workspace, and returns the output document. stats.seconds is the wall time
// (steady_clock) of polygon validation and pair evaluation only, not of JSON handling;
// stats.predicates/fallbacks sum the pairs' own counts (polygon validation is not counted).
// Returned as ordered_json so the keys keep the order shown above.
nlohmann::ordered_json run_pairs(const PairsInput& input, const PairsOverrides& overrides = {});

}  // namespace rockcontact::dynamics
