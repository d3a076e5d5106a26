#pragma once
// Checking someone else's kernel: `rockcontact pairs --compare THEIRS.json IN.json`, for polygon
// pairs (2D) and polyhedron pairs (IN has "dimension": 3).
//
// THEIRS is another kernel's answer to the pairs of IN, in the output schema of `rockcontact
// pairs` for IN's dimension (pairs_io.hpp) with every field optional except results[].id, so
// that a kernel reports only what it computes. In 2D:
//   {"policy"?, "demarcation"?,                  (if present, as in our output; shown, not used)
//    "results": [{"id", "status"?, "ip"?, "area"?, "force"?, "point"? ([x, y] or null),
//                 "fallbacks"?}
//              | {"id", "status": "error", "error"?}],
//    "stats"?: {"pairs"?, "predicates"?, "fallbacks"?, "seconds"?}}
// In 3D (no "demarcation"):
//   {"policy"?,
//    "results": [{"id", "status"?, "volume"?, "distance"? (a number or null),
//                 "penetration"? ({"depth"?, "normal"? (non-zero [nx, ny, nz])} or null),
//                 "contact_set"? ({"dimension"? (0, 1 or 2), "vertices"? ([[x, y, z], ...])}
//                                 or null),
//                 "constraints"? ([{"type"?, "point_cp"?, "point_tp"?, "normal"?, "gap"?,
//                                   "force"?}, ...]), "fallbacks"?}
//              | {"id", "status": "error", "error"?}],
//    "stats"?: as in 2D}
// Unknown fields are errors, as everywhere in this project (InputError "<file>: <json path>:
// <problem>"); so are a duplicate id and an id that is not a pair of IN. Results are matched by
// id, in any order; a pair of IN without a result in THEIRS is a disagreement.
//
// Ours is computed from IN under --policy (default exact, whatever IN's "policy" says: the
// reference should be the exact answer) and, in 2D, --demarcation (default IN's). Each field
// that THEIRS gives is compared pair by pair. In both dimensions:
//   result   a result is present for the pair (always compared).
//   status   the verdict: equal or not. "error" (an invalid polygon or polyhedron) agrees only
//            with "error"; when either side is an error the verdict is the pair's only
//            comparison, and a result that gives values but no status for blocks we refuse
//            disagrees on it (theirs shown as null).
// In 2D:
//   ip_size  the number of IP vertices, equal or not (error: the difference of the counts).
//   ip       the symmetric Hausdorff distance between the two IP vertex sets, m, relative to
//            the pair's size D. As sets: vertex order and start vertex are ignored. It bounds the
//            Hausdorff distance between the polygons (the hulls of sets within e are within e),
//            and measures what a caller uses, the vertices; a vertex one side has in the middle
//            of an edge is far from every vertex of the other side and is counted, as it is by
//            ip_size. One side empty and the other not is a disagreement without a distance.
//   area     |theirs - ours|, m², relative to |ours|.
//   force    the Euclidean norm of the difference of the vectors, N/m, relative to |ours|: a
//            vector's error is not the error of its components (a small component may carry a
//            large relative error that does not matter).
//   point    the distance between the points, m, relative to D; null against a value (the one
//            side finds a force, the other none) is a disagreement without a distance.
// In 3D:
//   volume       |theirs - ours|, m³, relative to |ours|.
//   distance     |theirs - ours|, m, relative to ours; compared when theirs gives "distance";
//                null against a value (separate against not) is a disagreement without a number.
//   depth        the penetration depth, |theirs - ours|, m, relative to ours; compared when
//                theirs gives "penetration" as null or with a "depth"; null against a value is
//                a disagreement without a number.
//   normal       the angle between the penetration normals, rad, atan2(|a x b|, a . b) (accurate
//                for small angles, independent of the vectors' lengths), with a scale of 1: it
//                disagrees when the angle > atol + rtol. Compared when theirs gives a "normal";
//                against a null penetration of ours it is a disagreement without a number. It
//                is not compared when theirs also gives a depth that disagrees: the normal of a
//                wrong depth says nothing more. A direction of minimal penetration need not be
//                unique (a cube centred on a cube has six): two exact kernels may then report
//                different normals with equal depths, and this is reported as a normal
//                disagreement. Deciding whether theirs is another minimiser would need their
//                direction evaluated by our kernel; the report shows both normals instead.
//   contact_dimension  the contact set's dimension (0 point, 1 segment, 2 polygon), equal or
//                not; compared when theirs gives a contact set with a "dimension"; against a
//                null set of ours it is a disagreement without a number.
//   contact_set  the symmetric Hausdorff distance between the two corner sets, m, relative to
//                D, as for ip in 2D (corners in any order); compared when theirs gives
//                "contact_set" as null or with "vertices"; null against a set is a disagreement
//                without a distance.
//   constraints  the number of constraints listed, equal or not (error: the difference of the
//                counts). Their points, normals and gaps are read and checked for shape but not
//                compared: a constraint set is not unique (an edge-edge contact may equally be
//                listed as two vertex-face ones), so only its size is a property of the pair.
// D is the diagonal of the bounding box of cp ∪ tp (their vertices in 3D): a position has no
// scale of its own (|p| depends on where the origin is: at 1e9 m a relative error of 1e-9 would
// allow a metre), while D is translation invariant and is the lever arm that turns a point error
// into a moment error.
//
// Tolerance, numpy-style: a value disagrees when error > atol + rtol * scale, the scale being
// |ours| (area, force, volume, distance, depth), D (ip, point, contact_set) or 1 (normal); the
// relative error reported is error / scale (infinite when ours is zero and theirs is not). atol
// is in the field's own unit (m², N/m, m, m³ or rad). Counts and verdicts have no tolerance. The
// defaults, rtol 1e-9 and atol 0, are for checking a double kernel against the exact one: 1e-9
// is ~2^-30, a million times the rounding noise of an honest double computation on a
// well-conditioned pair (and loose enough for hand-typed decimals, 0.08 against
// 0.07999999999999999), so what it flags has lost more than 7 of its 16 digits, the mark of a
// cancellation or a wrong branch rather than of rounding. atol is 0 because no absolute scale
// fits every model (blocks of millimetres or kilometres, kn over orders of magnitude) and any
// atol would hide a wrong value smaller than itself, such as a sliver's whole area: with atol 0
// a zero of ours (the area and force of a touch, the volume of a touch) is matched only by zero.
// Far from the origin (|x| >> D) double cannot resolve positions to rtol * D (its spacing there
// is |x| * 2^-52), so positions need an --atol of a few such spacings.
//
// The comparison fails (the CLI exits 3) when any field disagrees: a verdict, a missing result,
// a count or dimension, a presence (null against a value) or an error above the tolerance.

#include <array>
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics {

enum class Verdict { separate, touch, overlap, error };

std::string_view to_string(Verdict verdict);
std::optional<Verdict> parse_verdict(std::string_view text);

// A 3D result's "penetration" when it is not null.
struct PenetrationRecord {
  std::optional<double> depth;          // m
  std::optional<kernel::Point3> normal;  // a non-zero direction (not necessarily unit)
};

// A 3D result's "contact_set" when it is not null.
struct ContactSetRecord {
  std::optional<int> dimension;                      // 0, 1 or 2
  std::optional<std::vector<kernel::Point3>> vertices;  // the corners, m, in any order
};

// One result of an output document, with the fields the document gives (those of its
// dimension; the others stay absent).
struct ResultRecord {
  std::size_t position = 0;  // index in the document's "results", for messages
  std::string id;
  std::optional<Verdict> status;
  std::optional<std::vector<kernel::Point2>> ip;
  std::optional<double> area;
  std::optional<kernel::Vector2> force;
  bool has_point = false;               // "point" present (as a value or as null)
  std::optional<kernel::Point2> point;  // its value when not null
  // 3D
  std::optional<double> volume;
  bool has_distance = false;  // "distance" present (as a value or as null)
  std::optional<double> distance;
  bool has_penetration = false;  // "penetration" present (as an object or as null)
  std::optional<PenetrationRecord> penetration;
  bool has_contact_set = false;  // "contact_set" present (as an object or as null)
  std::optional<ContactSetRecord> contact_set;
  std::optional<std::size_t> constraints;  // the number of constraints listed
};

struct ResultsDocument {
  std::string source;  // file name, for messages
  int dimension = 2;   // the schema it was read with
  std::optional<std::string> policy;
  std::optional<std::string> demarcation;
  std::vector<ResultRecord> results;  // in document order, ids unique
};

// Reads an output document of `dimension` (2 or 3, that of the input it answers) with the
// optional fields above. Throws InputError naming `source_name`, the field path and what was
// expected.
ResultsDocument parse_results(const nlohmann::json& document, const std::string& source_name,
                              int dimension = 2);
ResultsDocument read_results_file(const std::filesystem::path& file, int dimension = 2);

struct CompareOptions {
  double rtol = 1e-9;     // relative tolerance (>= 0)
  double atol = 0.0;      // absolute tolerance in each field's unit (>= 0)
  std::size_t worst = 5;  // worst cases kept per field
};

enum class Field {
  result, status,                              // both dimensions
  ip_size, ip, area, force, point,             // 2D
  volume, distance, depth, normal, contact_dimension, contact_set, constraints  // 3D
};
inline constexpr std::array<Field, 7> fields2d{Field::result, Field::status, Field::ip_size,
                                               Field::ip,     Field::area,   Field::force,
                                               Field::point};
inline constexpr std::array<Field, 9> fields3d{
    Field::result, Field::status,           Field::volume,      Field::distance,
    Field::depth,  Field::normal,           Field::contact_dimension,
    Field::contact_set, Field::constraints};
// The fields compared for inputs of `dimension` (2 or 3), in report order.
std::span<const Field> compared_fields(int dimension);
std::string_view to_string(Field field);

// One compared value of one pair.
struct FieldCase {
  PairSpec pair;    // the input in 2D: id, cp, tp (empty in 3D)
  Pair3Spec pair3;  // the input in 3D (empty in 2D)
  bool disagrees = false;
  std::optional<double> abs_error;  // absent for a verdict or presence difference
  std::optional<double> rel_error;  // absent where no scale applies (verdicts, counts)
  nlohmann::ordered_json ours;      // the compared values, as in the output schema
  nlohmann::ordered_json theirs;
};

struct FieldReport {
  Field field = Field::result;
  std::size_t compared = 0;
  std::size_t disagreements = 0;
  std::optional<double> max_abs;  // over the compared values that have one
  std::optional<double> max_rel;
  std::vector<std::string> disagreeing_ids;  // in input order
  // Up to CompareOptions::worst cases with a disagreement or a non-zero error: disagreements
  // first, those without a number (verdict, presence) first among them, then by relative error,
  // then by absolute error, both descending.
  std::vector<FieldCase> worst;
};

struct Comparison {
  int dimension = 2;  // of the input
  std::string input_source;
  std::string theirs_source;
  std::string policy;       // ours
  std::string demarcation;  // ours; "-" in 3D
  std::optional<std::string> their_policy;
  std::optional<std::string> their_demarcation;
  CompareOptions options;
  std::size_t pairs = 0;              // pairs of IN
  std::size_t pairs_disagreeing = 0;  // pairs with at least one disagreeing field
  std::vector<FieldReport> fields;  // those of compared_fields(dimension), in that order

  // The report of `f`; throws std::invalid_argument when `f` is not a field of the dimension.
  const FieldReport& field(Field f) const;
  bool agrees() const noexcept { return pairs_disagreeing == 0; }
};

// Compares `theirs` with `ours` (run_pairs's output for `input`, read back by parse_results),
// both read with the input's dimension. Throws InputError naming theirs.source for an id that
// is not a pair of `input`, and std::invalid_argument when a document's dimension is not the
// input's.
Comparison compare_results(const PairsInput& input, const ResultsDocument& ours,
                           const ResultsDocument& theirs, const CompareOptions& options);

// Computes ours (policy: overrides.policy, else exact; 2D demarcation: overrides, else input's)
// and compares.
Comparison compare_pairs(const PairsInput& input, const ResultsDocument& theirs,
                         const PairsOverrides& overrides, const CompareOptions& options);

// The report as JSON: {"dimension", "input", "theirs", "policy", "demarcation" (2D),
// "their_policy"?, "their_demarcation"?, "rtol", "atol", "pairs", "pairs_disagreeing", "agree",
// "fields": {NAME: {"compared", "disagreements", "max_abs", "max_rel", "disagreeing_ids",
// "worst": [{"id", "cp", "tp", "ours", "theirs", "abs_error", "rel_error", "disagrees"}]}}},
// NAME over compared_fields(dimension); cp and tp as in the input (3D: {"vertices", "faces"}).
// An error without a value is null; an infinite one is the string "inf" (JSON has no infinity).
nlohmann::ordered_json comparison_json(const Comparison& comparison);

// The report for a reader: a header, the table of fields (compared, disagreements, max
// absolute and relative error), the worst cases of each field with their inputs, and the
// summary line.
void write_comparison(std::ostream& out, const Comparison& comparison);

// One line: "compare: all 6 pairs agree ..." or "compare: 3 of 6 pairs disagree: status 1, ...".
std::string comparison_summary(const Comparison& comparison);

}  // namespace rockcontact::dynamics
