#pragma once
// Checking someone else's kernel: `rockcontact pairs --compare THEIRS.json IN.json`.
//
// THEIRS is another kernel's answer to the pairs of IN, in the output schema of `rockcontact
// pairs` (pairs_io.hpp) with every field optional except results[].id, so that a kernel reports
// only what it computes:
//   {"policy"?, "demarcation"?,                  (if present, as in our output; shown, not used)
//    "results": [{"id", "status"?, "ip"?, "area"?, "force"?, "point"? ([x, y] or null),
//                 "fallbacks"?}
//              | {"id", "status": "error", "error"?}],
//    "stats"?: {"pairs"?, "predicates"?, "fallbacks"?, "seconds"?}}
// Unknown fields are errors, as everywhere in this project (InputError "<file>: <json path>:
// <problem>"); so are a duplicate id and an id that is not a pair of IN. Results are matched by
// id, in any order; a pair of IN without a result in THEIRS is a disagreement.
//
// Ours is computed from IN under --policy (default exact, whatever IN's "policy" says: the
// reference should be the exact answer) and --demarcation (default IN's). Each field that THEIRS
// gives is compared pair by pair:
//   result   a result is present for the pair (always compared).
//   status   the verdict: equal or not. "error" (an invalid polygon) agrees only with "error";
//            when either side is an error the verdict is the pair's only comparison, and a
//            result that gives values but no status for polygons we refuse disagrees on it
//            (theirs shown as null).
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
// D is the diagonal of the bounding box of cp ∪ tp: a position has no scale of its own (|p|
// depends on where the origin is: at 1e9 m a relative error of 1e-9 would allow a metre), while
// D is translation invariant and is the lever arm that turns a point error into a moment error.
//
// Tolerance, numpy-style: a value disagrees when error > atol + rtol * scale, the scale being
// |ours| (area, force) or D (ip, point); the relative error reported is error / scale (infinite
// when ours is zero and theirs is not). atol is in the field's own unit (m², N/m or m). Counts
// and verdicts have no tolerance. The defaults, rtol 1e-9 and atol 0, are for checking a double
// kernel against the exact one: 1e-9 is ~2^-30, a million times the rounding noise of an honest
// double computation on a well-conditioned pair (and loose enough for hand-typed decimals, 0.08
// against 0.07999999999999999), so what it flags has lost more than 7 of its 16 digits, the mark
// of a cancellation or a wrong branch rather than of rounding. atol is 0 because no absolute scale
// fits every model (blocks of millimetres or kilometres, kn over orders of magnitude) and any
// atol would hide a wrong value smaller than itself, such as a sliver's whole area: with atol 0
// a zero of ours (the area and force of a touch) is matched only by zero. Far from the origin
// (|x| >> D) double cannot resolve positions to rtol * D (its spacing there is |x| * 2^-52), so
// positions need an --atol of a few such spacings.
//
// The comparison fails (the CLI exits 3) when any field disagrees: a verdict, a missing result,
// a vertex count, a presence (point null against a value) or an error above the tolerance.

#include <array>
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::dynamics {

enum class Verdict { separate, touch, overlap, error };

std::string_view to_string(Verdict verdict);
std::optional<Verdict> parse_verdict(std::string_view text);

// One result of an output document, with the fields the document gives.
struct ResultRecord {
  std::size_t position = 0;  // index in the document's "results", for messages
  std::string id;
  std::optional<Verdict> status;
  std::optional<std::vector<kernel::Point2>> ip;
  std::optional<double> area;
  std::optional<kernel::Vector2> force;
  bool has_point = false;               // "point" present (as a value or as null)
  std::optional<kernel::Point2> point;  // its value when not null
};

struct ResultsDocument {
  std::string source;  // file name, for messages
  std::optional<std::string> policy;
  std::optional<std::string> demarcation;
  std::vector<ResultRecord> results;  // in document order, ids unique
};

// Reads an output document with the optional fields above. Throws InputError naming
// `source_name`, the field path and what was expected.
ResultsDocument parse_results(const nlohmann::json& document, const std::string& source_name);
ResultsDocument read_results_file(const std::filesystem::path& file);

struct CompareOptions {
  double rtol = 1e-9;     // relative tolerance (>= 0)
  double atol = 0.0;      // absolute tolerance in each field's unit (>= 0)
  std::size_t worst = 5;  // worst cases kept per field
};

enum class Field { result, status, ip_size, ip, area, force, point };
inline constexpr std::array<Field, 7> all_fields{Field::result, Field::status, Field::ip_size,
                                                 Field::ip,     Field::area,   Field::force,
                                                 Field::point};
std::string_view to_string(Field field);

// One compared value of one pair.
struct FieldCase {
  PairSpec pair;  // the input: id, cp, tp
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
  std::string input_source;
  std::string theirs_source;
  std::string policy;       // ours
  std::string demarcation;  // ours
  std::optional<std::string> their_policy;
  std::optional<std::string> their_demarcation;
  CompareOptions options;
  std::size_t pairs = 0;              // pairs of IN
  std::size_t pairs_disagreeing = 0;  // pairs with at least one disagreeing field
  std::array<FieldReport, all_fields.size()> fields;

  const FieldReport& field(Field f) const { return fields[static_cast<std::size_t>(f)]; }
  bool agrees() const noexcept { return pairs_disagreeing == 0; }
};

// Compares `theirs` with `ours` (run_pairs's output for `input`, read back by parse_results).
// Throws InputError naming theirs.source for an id that is not a pair of `input`.
Comparison compare_results(const PairsInput& input, const ResultsDocument& ours,
                           const ResultsDocument& theirs, const CompareOptions& options);

// Computes ours (policy: overrides.policy, else exact; demarcation: overrides, else input's)
// and compares.
Comparison compare_pairs(const PairsInput& input, const ResultsDocument& theirs,
                         const PairsOverrides& overrides, const CompareOptions& options);

// The report as JSON: {"input", "theirs", "policy", "demarcation", "their_policy"?,
// "their_demarcation"?, "rtol", "atol", "pairs", "pairs_disagreeing", "agree",
// "fields": {NAME: {"compared", "disagreements", "max_abs", "max_rel", "disagreeing_ids",
// "worst": [{"id", "cp", "tp", "ours", "theirs", "abs_error", "rel_error", "disagrees"}]}}}.
// An error without a value is null; an infinite one is the string "inf" (JSON has no infinity).
nlohmann::ordered_json comparison_json(const Comparison& comparison);

// The report for a reader: a header, the table of fields (compared, disagreements, max
// absolute and relative error), the worst cases of each field with their inputs, and the
// summary line.
void write_comparison(std::ostream& out, const Comparison& comparison);

// One line: "compare: all 6 pairs agree ..." or "compare: 3 of 6 pairs disagree: status 1, ...".
std::string comparison_summary(const Comparison& comparison);

}  // namespace rockcontact::dynamics
