#include "rockcontact/dynamics/apps/pairs_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <ostream>
#include <span>
#include <unordered_map>
#include <utility>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::dynamics {

namespace {

using kernel::Point2;
using nlohmann::json;
using nlohmann::ordered_json;

constexpr double infinity = std::numeric_limits<double>::infinity();

// ---- Reading the output schema with optional fields

constexpr JsonField document_fields[] = {
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"demarcation", false, "one of \"paper\", \"exact\""},
    {"results", true, "an array of results {\"id\", ...}, at most one per pair"},
    {"stats", false,
     "an object {\"pairs\", \"predicates\", \"fallbacks\", \"seconds\"}, each member optional"},
};
constexpr JsonField stats_fields[] = {
    {"pairs", false, "the number of pairs, an integer >= 0"},
    {"predicates", false, "the number of predicate calls, an integer >= 0"},
    {"fallbacks", false, "the number of exact fallbacks, an integer >= 0"},
    {"seconds", false, "the run time in s, a finite number >= 0"},
};
constexpr JsonField result_fields[] = {
    {"id", true, "the id of a pair of the input, a string"},
    {"status", false, "one of \"separate\", \"touch\", \"overlap\", \"error\""},
    {"ip", false, "the intersection polygon, an array of [x, y] vertices"},
    {"area", false, "the IP area in m², a finite number"},
    {"force", false, "the normal force on cp in N/m, an array [fx, fy] of finite numbers"},
    {"point", false, "the contact point, an array [x, y] of finite numbers, or null"},
    {"fallbacks", false, "the number of exact fallbacks, an integer >= 0"},
};
// A result whose status is "error" carries its message and nothing computed.
constexpr JsonField error_result_fields[] = {
    {"id", true, "the id of a pair of the input, a string"},
    {"status", true, "\"error\""},
    {"error", false, "the message, a string"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

void read_count(const JsonReader& reader, const json& value, const std::string& path,
                std::string_view what) {
  if (reader.integer(value, path, what) < 0) reader.fail_expected(path, what, value);
}

void check_stats(const JsonReader& reader, const json& value) {
  reader.check_object(value, "stats", expected(document_fields, "stats"), stats_fields);
  for (const std::string_view name : {"pairs", "predicates", "fallbacks"}) {
    if (value.contains(name)) {
      read_count(reader, value.at(name), json_child("stats", name), expected(stats_fields, name));
    }
  }
  if (value.contains("seconds")) {
    reader.non_negative(value.at("seconds"), "stats.seconds", expected(stats_fields, "seconds"));
  }
}

kernel::Vector2 read_vector(const JsonReader& reader, const json& value, const std::string& path,
                            std::string_view what) {
  const std::vector<double> xy = reader.numbers(value, path, 2, what);
  return {xy[0], xy[1]};
}

// The computed fields of a result that is not an error.
void read_values(const JsonReader& reader, const json& value, const std::string& path,
                 ResultRecord& r) {
  const auto field = [&](std::string_view name) { return json_child(path, name); };
  if (value.contains("ip")) {
    r.ip = reader.polygon(value.at("ip"), field("ip"), expected(result_fields, "ip"));
  }
  if (value.contains("area")) {
    r.area = reader.number(value.at("area"), field("area"), expected(result_fields, "area"));
  }
  if (value.contains("force")) {
    r.force =
        read_vector(reader, value.at("force"), field("force"), expected(result_fields, "force"));
  }
  if (value.contains("point")) {
    r.has_point = true;
    if (!value.at("point").is_null()) {
      const auto p =
          read_vector(reader, value.at("point"), field("point"), expected(result_fields, "point"));
      r.point = Point2{p.x, p.y};
    }
  }
  if (value.contains("fallbacks")) {
    read_count(reader, value.at("fallbacks"), field("fallbacks"),
               expected(result_fields, "fallbacks"));
  }
}

ResultRecord read_result(const JsonReader& reader, const json& value, const std::string& path,
                         std::size_t position) {
  const bool error = value.is_object() && value.contains("status") && value.at("status") == "error";
  if (value.is_object() && !error && value.contains("error")) {
    reader.fail(json_child(path, "error"),
                "an error message belongs to a result with \"status\": \"error\"; expected no "
                "\"error\" here");
  }
  reader.check_object(value, path, "a result, an object {\"id\", ...}",
                      error ? std::span<const JsonField>(error_result_fields) : result_fields);
  ResultRecord r;
  r.position = position;
  r.id = reader.string(value.at("id"), json_child(path, "id"), expected(result_fields, "id"));
  if (value.contains("status")) {
    r.status = reader.choice(value.at("status"), json_child(path, "status"),
                             expected(result_fields, "status"), &parse_verdict);
  }
  if (error) {
    if (value.contains("error")) {
      reader.string(value.at("error"), json_child(path, "error"),
                    expected(error_result_fields, "error"));
    }
  } else {
    read_values(reader, value, path, r);
  }
  return r;
}

// ---- Measuring one field of one pair

// The diagonal of the bounding box of cp ∪ tp: the scale of positions (see the header).
double pair_size(const PairSpec& pair) {
  double min_x = infinity, min_y = infinity, max_x = -infinity, max_y = -infinity;
  for (const auto* polygon : {&pair.cp, &pair.tp}) {
    for (const Point2& p : *polygon) {
      min_x = std::min(min_x, p.x);
      min_y = std::min(min_y, p.y);
      max_x = std::max(max_x, p.x);
      max_y = std::max(max_y, p.y);
    }
  }
  return std::hypot(max_x - min_x, max_y - min_y);
}

double distance(const Point2& a, const Point2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

double directed_hausdorff(const std::vector<Point2>& from, const std::vector<Point2>& to) {
  double farthest = 0.0;
  for (const Point2& p : from) {
    double nearest = infinity;
    for (const Point2& q : to) nearest = std::min(nearest, distance(p, q));
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

ordered_json point_json(const Point2& p) { return ordered_json::array({p.x, p.y}); }

ordered_json polygon_json(const std::vector<Point2>& vertices) {
  ordered_json out = ordered_json::array();
  for (const Point2& p : vertices) out.push_back(point_json(p));
  return out;
}

// The value a result gives for `field`, as written in the output schema; nullopt when absent.
std::optional<ordered_json> field_value(const ResultRecord& r, Field field) {
  switch (field) {
    case Field::result:
      return ordered_json(r.status ? to_string(*r.status) : std::string_view("present"));
    case Field::status:
      return r.status ? std::optional(ordered_json(to_string(*r.status))) : std::nullopt;
    case Field::ip_size:
      return r.ip ? std::optional(ordered_json(r.ip->size())) : std::nullopt;
    case Field::ip:
      return r.ip ? std::optional(polygon_json(*r.ip)) : std::nullopt;
    case Field::area:
      return r.area ? std::optional(ordered_json(*r.area)) : std::nullopt;
    case Field::force:
      return r.force ? std::optional(ordered_json::array({r.force->x, r.force->y})) : std::nullopt;
    case Field::point:
      if (!r.has_point) return std::nullopt;
      return r.point ? point_json(*r.point) : ordered_json(nullptr);
  }
  return std::nullopt;
}

// A difference without a number: verdicts, presence. Disagrees when the values differ.
FieldCase discrete(ordered_json ours, ordered_json theirs) {
  FieldCase c;
  c.disagrees = ours != theirs;
  c.ours = std::move(ours);
  c.theirs = std::move(theirs);
  return c;
}

FieldCase measured(double error, double scale, const CompareOptions& options, ordered_json ours,
                   ordered_json theirs) {
  FieldCase c;
  c.abs_error = error;
  c.rel_error = error == 0.0 ? 0.0 : scale > 0.0 ? error / scale : infinity;
  c.disagrees = !(error <= options.atol + options.rtol * scale);  // a NaN disagrees
  c.ours = std::move(ours);
  c.theirs = std::move(theirs);
  return c;
}

FieldCase measure_ip(const std::vector<Point2>& ours, const std::vector<Point2>& theirs,
                     double size, const CompareOptions& options) {
  if (ours.empty() != theirs.empty()) return discrete(polygon_json(ours), polygon_json(theirs));
  const double error = std::max(directed_hausdorff(ours, theirs), directed_hausdorff(theirs, ours));
  return measured(error, size, options, polygon_json(ours), polygon_json(theirs));
}

FieldCase measure_point(const std::optional<Point2>& ours, const std::optional<Point2>& theirs,
                        double size, const CompareOptions& options) {
  if (!ours || !theirs) {
    return discrete(ours ? point_json(*ours) : nullptr, theirs ? point_json(*theirs) : nullptr);
  }
  return measured(distance(*ours, *theirs), size, options, point_json(*ours), point_json(*theirs));
}

// `field` of two results that are not errors; `theirs` gives the field.
FieldCase measure(Field field, const ResultRecord& ours, const ResultRecord& theirs, double size,
                  const CompareOptions& options) {
  switch (field) {
    case Field::ip_size: {
      const std::size_t a = ours.ip.value().size(), b = theirs.ip->size();
      FieldCase c = discrete(a, b);
      c.abs_error = static_cast<double>(a > b ? a - b : b - a);
      return c;
    }
    case Field::ip:
      return measure_ip(ours.ip.value(), *theirs.ip, size, options);
    case Field::area:
      return measured(std::abs(*theirs.area - ours.area.value()), std::abs(*ours.area), options,
                      *ours.area, *theirs.area);
    case Field::force: {
      const kernel::Vector2 a = ours.force.value(), b = *theirs.force;
      return measured(std::hypot(b.x - a.x, b.y - a.y), std::hypot(a.x, a.y), options,
                      *field_value(ours, field), *field_value(theirs, field));
    }
    case Field::point:
      return measure_point(ours.point, theirs.point, size, options);
    case Field::result:
    case Field::status:
      break;  // verdicts: equal or not
  }
  return discrete(*field_value(ours, field), *field_value(theirs, field));
}

// ---- Accumulating the cases into the report

class Tally {
 public:
  explicit Tally(Comparison& comparison) : comparison_(comparison) {}

  void add(Field field, const PairSpec& pair, FieldCase c) {
    FieldReport& report = comparison_.fields[static_cast<std::size_t>(field)];
    ++report.compared;
    if (c.abs_error) report.max_abs = std::max(report.max_abs.value_or(0.0), *c.abs_error);
    if (c.rel_error) report.max_rel = std::max(report.max_rel.value_or(0.0), *c.rel_error);
    if (c.disagrees) {
      ++report.disagreements;
      report.disagreeing_ids.push_back(pair.id);
      pair_disagrees_ = true;
    }
    if (c.disagrees || c.abs_error.value_or(0.0) > 0.0) {
      c.pair = pair;
      report.worst.push_back(std::move(c));
    }
  }

  // Whether the pair just compared had a disagreement; starts the next pair.
  bool end_pair() { return std::exchange(pair_disagrees_, false); }

 private:
  Comparison& comparison_;
  bool pair_disagrees_ = false;
};

constexpr Field value_fields[] = {Field::ip_size, Field::ip, Field::area, Field::force,
                                  Field::point};

void compare_pair(Tally& tally, const PairSpec& pair, const ResultRecord& ours,
                  const ResultRecord* theirs, const CompareOptions& options) {
  if (!theirs) {
    tally.add(Field::result, pair, discrete(*field_value(ours, Field::result), "missing"));
    return;
  }
  tally.add(Field::result, pair, FieldCase{});
  const bool gives_values = theirs->ip || theirs->area || theirs->force || theirs->has_point;
  const bool one_is_error =
      ours.status.value() == Verdict::error || theirs->status == Verdict::error;
  // The verdict when theirs gives one; and values without a status for polygons we refuse
  // disagree with the refusal, as a verdict (theirs shown as null).
  if (theirs->status || (one_is_error && gives_values)) {
    tally.add(Field::status, pair,
              discrete(*field_value(ours, Field::status),
                       field_value(*theirs, Field::status).value_or(nullptr)));
  }
  if (one_is_error) return;  // one side computed nothing
  const double size = pair_size(pair);
  for (const Field field : value_fields) {
    if (field_value(*theirs, field)) {
      tally.add(field, pair, measure(field, ours, *theirs, size, options));
    }
  }
}

// Disagreements first, those without a number first among them; then larger relative, then
// larger absolute errors.
bool worse(const FieldCase& a, const FieldCase& b) {
  if (a.disagrees != b.disagrees) return a.disagrees;
  if (a.abs_error.has_value() != b.abs_error.has_value()) return !a.abs_error;
  if (a.rel_error.value_or(-1.0) != b.rel_error.value_or(-1.0)) {
    return a.rel_error.value_or(-1.0) > b.rel_error.value_or(-1.0);
  }
  return a.abs_error.value_or(-1.0) > b.abs_error.value_or(-1.0);
}

void keep_worst(FieldReport& report, std::size_t count) {
  std::stable_sort(report.worst.begin(), report.worst.end(), worse);
  if (report.worst.size() > count) report.worst.resize(count);
}

// THEIRS's results by id; an id that is not a pair of the input is an error in THEIRS.
std::unordered_map<std::string, const ResultRecord*> index_theirs(const PairsInput& input,
                                                                  const ResultsDocument& theirs) {
  std::unordered_map<std::string, bool> input_ids;
  for (const PairSpec& pair : input.pairs) input_ids.emplace(pair.id, true);
  std::unordered_map<std::string, const ResultRecord*> by_id;
  const JsonReader reader(theirs.source);
  for (const ResultRecord& r : theirs.results) {
    if (!input_ids.contains(r.id)) {
      reader.fail_expected(json_child(json_element("results", r.position), "id"),
                           "the id of a pair of " + input.source, json(r.id));
    }
    by_id.emplace(r.id, &r);
  }
  return by_id;
}

// ---- Writing the report

// An error to three digits, "-" when there is none.
std::string error_text(const std::optional<double>& value) {
  if (!value) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", *value);
  return text;
}

// A tolerance as the user typed it (%g keeps six digits).
std::string tolerance_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

ordered_json error_json(const std::optional<double>& value) {
  if (!value) return nullptr;
  if (std::isinf(*value)) return "inf";
  return *value;
}

ordered_json case_json(const FieldCase& c) {
  ordered_json out;
  out["id"] = c.pair.id;
  out["cp"] = polygon_json(c.pair.cp);
  out["tp"] = polygon_json(c.pair.tp);
  out["ours"] = c.ours;
  out["theirs"] = c.theirs;
  out["abs_error"] = error_json(c.abs_error);
  out["rel_error"] = error_json(c.rel_error);
  out["disagrees"] = c.disagrees;
  return out;
}

ordered_json field_json(const FieldReport& report) {
  ordered_json worst = ordered_json::array();
  for (const FieldCase& c : report.worst) worst.push_back(case_json(c));
  ordered_json out;
  out["compared"] = report.compared;
  out["disagreements"] = report.disagreements;
  out["max_abs"] = error_json(report.max_abs);
  out["max_rel"] = error_json(report.max_rel);
  out["disagreeing_ids"] = report.disagreeing_ids;
  out["worst"] = std::move(worst);
  return out;
}

void write_header(std::ostream& out, const Comparison& c) {
  out << "theirs " << c.theirs_source << " against ours (policy " << c.policy << ", demarcation "
      << c.demarcation << ") on " << c.input_source << '\n';
  if (c.their_policy || c.their_demarcation) {
    out << "theirs says: policy " << c.their_policy.value_or("-") << ", demarcation "
        << c.their_demarcation.value_or("-") << '\n';
  }
  out << "a value disagrees when error > atol + rtol * scale; rtol "
      << tolerance_text(c.options.rtol) << ", atol " << tolerance_text(c.options.atol) << "\n\n";
}

void write_table(std::ostream& out, const Comparison& c) {
  out << std::left << std::setw(10) << "field" << std::setw(10) << "compared" << std::setw(10)
      << "disagree" << std::setw(14) << "max abs err"
      << "max rel err\n";
  for (const FieldReport& r : c.fields) {
    out << std::setw(10) << to_string(r.field) << std::setw(10) << r.compared << std::setw(10)
        << r.disagreements;
    if (r.compared == 0) {
      out << "not compared (absent from theirs)\n";
      continue;
    }
    out << std::setw(14) << error_text(r.max_abs) << error_text(r.max_rel) << '\n';
  }
  out << std::right;
}

void write_worst(std::ostream& out, const FieldReport& r) {
  out << "\nworst " << to_string(r.field) << ": " << r.disagreements << " of " << r.compared
      << " disagree; " << r.worst.size() << " case" << (r.worst.size() == 1 ? "" : "s")
      << " shown\n";
  for (const FieldCase& c : r.worst) {
    out << "  " << c.pair.id << ": ours " << c.ours.dump() << ", theirs " << c.theirs.dump();
    if (c.abs_error) out << "; error " << error_text(c.abs_error);
    if (c.rel_error) out << " (relative " << error_text(c.rel_error) << ')';
    out << (c.disagrees ? "  DISAGREES" : "  within tolerance") << '\n'
        << "    cp " << polygon_json(c.pair.cp).dump() << "\n    tp "
        << polygon_json(c.pair.tp).dump() << '\n';
  }
}

}  // namespace

std::string_view to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::separate:
      return "separate";
    case Verdict::touch:
      return "touch";
    case Verdict::overlap:
      return "overlap";
    case Verdict::error:
      return "error";
  }
  return "?";
}

std::optional<Verdict> parse_verdict(std::string_view text) {
  for (const Verdict v : {Verdict::separate, Verdict::touch, Verdict::overlap, Verdict::error}) {
    if (text == to_string(v)) return v;
  }
  return std::nullopt;
}

std::string_view to_string(Field field) {
  constexpr std::string_view names[] = {"result", "status", "ip_size", "ip",
                                        "area",   "force",  "point"};
  return names[static_cast<std::size_t>(field)];
}

ResultsDocument parse_results(const json& document, const std::string& source_name) {
  const JsonReader reader(source_name);
  reader.check_object(document, "", "a JSON object {\"results\", ...}", document_fields);
  ResultsDocument out;
  out.source = source_name;
  if (document.contains("policy")) {
    out.policy = kernel::to_string(reader.choice(document.at("policy"), "policy",
                                                 expected(document_fields, "policy"),
                                                 &kernel::parse_policy));
  }
  if (document.contains("demarcation")) {
    out.demarcation = kernel::to_string(reader.choice(document.at("demarcation"), "demarcation",
                                                      expected(document_fields, "demarcation"),
                                                      &kernel::parse_demarcation));
  }
  if (document.contains("stats")) check_stats(reader, document.at("stats"));
  const json& results = document.at("results");
  if (!results.is_array())
    reader.fail_expected("results", expected(document_fields, "results"), results);
  UniqueIds ids;
  for (std::size_t i = 0; i < results.size(); ++i) {
    out.results.push_back(read_result(reader, results[i], json_element("results", i), i));
    ids.add(reader, "results", i, out.results.back().id);
  }
  return out;
}

ResultsDocument read_results_file(const std::filesystem::path& file) {
  return parse_results(read_json_file(file), file.string());
}

Comparison compare_results(const PairsInput& input, const ResultsDocument& ours,
                           const ResultsDocument& theirs, const CompareOptions& options) {
  Comparison c;
  c.input_source = input.source;
  c.theirs_source = theirs.source;
  c.policy = ours.policy.value_or("-");
  c.demarcation = ours.demarcation.value_or("-");
  c.their_policy = theirs.policy;
  c.their_demarcation = theirs.demarcation;
  c.options = options;
  c.pairs = input.pairs.size();
  for (std::size_t f = 0; f < all_fields.size(); ++f) c.fields[f].field = all_fields[f];
  const auto by_id = index_theirs(input, theirs);
  Tally tally(c);
  for (std::size_t i = 0; i < input.pairs.size(); ++i) {
    const auto found = by_id.find(input.pairs[i].id);
    compare_pair(tally, input.pairs[i], ours.results.at(i),
                 found == by_id.end() ? nullptr : found->second, options);
    if (tally.end_pair()) ++c.pairs_disagreeing;
  }
  for (FieldReport& report : c.fields) keep_worst(report, options.worst);
  return c;
}

Comparison compare_pairs(const PairsInput& input, const ResultsDocument& theirs,
                         const PairsOverrides& overrides, const CompareOptions& options) {
  PairsOverrides ours_overrides = overrides;
  ours_overrides.policy = overrides.policy.value_or(kernel::PolicyKind::exact);
  if (ours_overrides.policy == kernel::PolicyKind::exact) {
    // Exact shares Filtered's staged predicates; a pass under Checked first compares every
    // sign with its own exact evaluation, so a filter bug stops the comparison with the
    // predicate's input (PolicyDisagreement) instead of passing for the reference.
    PairsOverrides checked = overrides;
    checked.policy = kernel::PolicyKind::checked;
    static_cast<void>(run_pairs(input, checked));
  }
  // Read back through the same reader as theirs, so both sides are the same kind of record.
  const ResultsDocument ours = parse_results(json(run_pairs(input, ours_overrides)), "ours");
  return compare_results(input, ours, theirs, options);
}

ordered_json comparison_json(const Comparison& c) {
  ordered_json out;
  out["input"] = c.input_source;
  out["theirs"] = c.theirs_source;
  out["policy"] = c.policy;
  out["demarcation"] = c.demarcation;
  if (c.their_policy) out["their_policy"] = *c.their_policy;
  if (c.their_demarcation) out["their_demarcation"] = *c.their_demarcation;
  out["rtol"] = c.options.rtol;
  out["atol"] = c.options.atol;
  out["pairs"] = c.pairs;
  out["pairs_disagreeing"] = c.pairs_disagreeing;
  out["agree"] = c.agrees();
  ordered_json fields;
  for (const FieldReport& report : c.fields)
    fields[std::string(to_string(report.field))] = field_json(report);
  out["fields"] = std::move(fields);
  return out;
}

void write_comparison(std::ostream& out, const Comparison& comparison) {
  write_header(out, comparison);
  write_table(out, comparison);
  for (const FieldReport& report : comparison.fields) {
    if (!report.worst.empty()) write_worst(out, report);
  }
  out << '\n' << comparison_summary(comparison) << '\n';
}

std::string comparison_summary(const Comparison& c) {
  std::string disagreeing, absent;
  for (const FieldReport& r : c.fields) {
    // A missing result reads better as "missing" than as a field called "result".
    const std::string name = r.field == Field::result ? "missing" : std::string(to_string(r.field));
    if (r.disagreements > 0) {
      disagreeing +=
          (disagreeing.empty() ? "" : ", ") + name + ' ' + std::to_string(r.disagreements);
    }
    if (r.compared == 0 && r.field != Field::result) absent += (absent.empty() ? "" : ", ") + name;
  }
  std::string line = c.agrees()
                         ? "compare: all " + std::to_string(c.pairs) + " pairs agree"
                         : "compare: " + std::to_string(c.pairs_disagreeing) + " of " +
                               std::to_string(c.pairs) + " pairs disagree (" + disagreeing + ")";
  if (!absent.empty()) line += "; not compared: " + absent;
  return line + "; rtol " + tolerance_text(c.options.rtol) + ", atol " +
         tolerance_text(c.options.atol);
}

}  // namespace rockcontact::dynamics
