#include "rockcontact/dynamics/apps/pairs_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <ostream>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::dynamics {

namespace {

using kernel::Point2;
using kernel::Point3;
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
constexpr JsonField document3_fields[] = {
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
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
constexpr JsonField result3_fields[] = {
    {"id", true, "the id of a pair of the input, a string"},
    {"status", false, "one of \"separate\", \"touch\", \"overlap\", \"error\""},
    {"volume", false, "the intersection volume in m³, a finite number"},
    {"distance", false, "the distance in m, a finite number, or null"},
    {"penetration", false,
     "an object {\"depth\", \"normal\"}, each member optional, or null"},
    {"contact_set", false,
     "an object {\"dimension\", \"vertices\"}, each member optional, or null"},
    {"constraints", false, "an array of constraints {\"type\", \"point_cp\", ...}"},
    {"fallbacks", false, "the number of exact fallbacks, an integer >= 0"},
};
constexpr JsonField penetration_fields[] = {
    {"depth", false, "the penetration depth in m, a finite number"},
    {"normal", false, "the penetration normal, an array [nx, ny, nz] of finite numbers, not all 0"},
};
constexpr JsonField contact_set_fields[] = {
    {"dimension", false, "the dimension of the contact set, 0, 1 or 2"},
    {"vertices", false, "the corners of the contact set, an array of [x, y, z] vertices"},
};
constexpr JsonField constraint_fields[] = {
    {"type", false,
     "one of \"vertex-face\", \"edge-edge\", \"vertex-edge\", \"vertex-vertex\""},
    {"point_cp", false, "a point of cp, an array [x, y, z] of finite numbers"},
    {"point_tp", false, "a point of tp, an array [x, y, z] of finite numbers"},
    {"normal", false, "the contact normal, an array [nx, ny, nz] of finite numbers"},
    {"gap", false, "the gap in m, a finite number"},
    {"force", false, "the force on tp in N, an array [fx, fy, fz] of finite numbers"},
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

Point3 read_point3(const JsonReader& reader, const json& value, const std::string& path,
                   std::string_view what) {
  const std::vector<double> xyz = reader.numbers(value, path, 3, what);
  return {xyz[0], xyz[1], xyz[2]};
}

std::vector<Point3> read_points3(const JsonReader& reader, const json& value,
                                 const std::string& path, std::string_view what) {
  if (!value.is_array()) reader.fail_expected(path, what, value);
  std::vector<Point3> points;
  for (std::size_t i = 0; i < value.size(); ++i) {
    points.push_back(read_point3(reader, value[i], json_element(path, i),
                                 "a vertex, an [x, y, z] triple of finite numbers"));
  }
  return points;
}

PenetrationRecord read_penetration(const JsonReader& reader, const json& value,
                                   const std::string& path) {
  reader.check_object(value, path, expected(result3_fields, "penetration"), penetration_fields);
  PenetrationRecord out;
  if (value.contains("depth")) {
    out.depth = reader.number(value.at("depth"), json_child(path, "depth"),
                              expected(penetration_fields, "depth"));
  }
  if (value.contains("normal")) {
    const std::string normal_path = json_child(path, "normal");
    const std::string_view what = expected(penetration_fields, "normal");
    const Point3 n = read_point3(reader, value.at("normal"), normal_path, what);
    // A zero vector has no direction: the angle to ours would be undefined.
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) {
      reader.fail_expected(normal_path, what, value.at("normal"));
    }
    out.normal = n;
  }
  return out;
}

ContactSetRecord read_contact_set(const JsonReader& reader, const json& value,
                                  const std::string& path) {
  reader.check_object(value, path, expected(result3_fields, "contact_set"), contact_set_fields);
  ContactSetRecord out;
  if (value.contains("dimension")) {
    const std::string_view what = expected(contact_set_fields, "dimension");
    const std::int64_t d =
        reader.integer(value.at("dimension"), json_child(path, "dimension"), what);
    if (d < 0 || d > 2) {
      reader.fail_expected(json_child(path, "dimension"), what, value.at("dimension"));
    }
    out.dimension = static_cast<int>(d);
  }
  if (value.contains("vertices")) {
    out.vertices = read_points3(reader, value.at("vertices"), json_child(path, "vertices"),
                                expected(contact_set_fields, "vertices"));
  }
  return out;
}

bool is_constraint_type(const std::string& type) {
  return type == "vertex-face" || type == "edge-edge" || type == "vertex-edge" ||
         type == "vertex-vertex";
}

// Checks each constraint's shape and returns their number (only the number is compared).
std::size_t read_constraints(const JsonReader& reader, const json& value, const std::string& path) {
  if (!value.is_array()) reader.fail_expected(path, expected(result3_fields, "constraints"), value);
  for (std::size_t i = 0; i < value.size(); ++i) {
    const json& c = value[i];
    const std::string at = json_element(path, i);
    reader.check_object(c, at, "a constraint, an object {\"type\", \"point_cp\", ...}",
                        constraint_fields);
    if (c.contains("type")) {
      const std::string_view what = expected(constraint_fields, "type");
      if (!is_constraint_type(reader.string(c.at("type"), json_child(at, "type"), what))) {
        reader.fail_expected(json_child(at, "type"), what, c.at("type"));
      }
    }
    for (const std::string_view name : {"point_cp", "point_tp", "normal", "force"}) {
      if (c.contains(name)) {
        read_point3(reader, c.at(name), json_child(at, name), expected(constraint_fields, name));
      }
    }
    if (c.contains("gap")) {
      reader.number(c.at("gap"), json_child(at, "gap"), expected(constraint_fields, "gap"));
    }
  }
  return value.size();
}

// The computed fields of a 3D result that is not an error.
void read_values3(const JsonReader& reader, const json& value, const std::string& path,
                  ResultRecord& r) {
  const auto field = [&](std::string_view name) { return json_child(path, name); };
  if (value.contains("volume")) {
    r.volume =
        reader.number(value.at("volume"), field("volume"), expected(result3_fields, "volume"));
  }
  if (value.contains("distance")) {
    r.has_distance = true;
    if (!value.at("distance").is_null()) {
      r.distance = reader.number(value.at("distance"), field("distance"),
                                 expected(result3_fields, "distance"));
    }
  }
  if (value.contains("penetration")) {
    r.has_penetration = true;
    if (!value.at("penetration").is_null()) {
      r.penetration = read_penetration(reader, value.at("penetration"), field("penetration"));
    }
  }
  if (value.contains("contact_set")) {
    r.has_contact_set = true;
    if (!value.at("contact_set").is_null()) {
      r.contact_set = read_contact_set(reader, value.at("contact_set"), field("contact_set"));
    }
  }
  if (value.contains("constraints")) {
    r.constraints = read_constraints(reader, value.at("constraints"), field("constraints"));
  }
  if (value.contains("fallbacks")) {
    read_count(reader, value.at("fallbacks"), field("fallbacks"),
               expected(result3_fields, "fallbacks"));
  }
}

ResultRecord read_result(const JsonReader& reader, const json& value, const std::string& path,
                         std::size_t position, int dimension) {
  const std::span<const JsonField> value_fields =
      dimension == 3 ? std::span<const JsonField>(result3_fields) : result_fields;
  const bool error = value.is_object() && value.contains("status") && value.at("status") == "error";
  if (value.is_object() && !error && value.contains("error")) {
    reader.fail(json_child(path, "error"),
                "an error message belongs to a result with \"status\": \"error\"; expected no "
                "\"error\" here");
  }
  reader.check_object(value, path, "a result, an object {\"id\", ...}",
                      error ? std::span<const JsonField>(error_result_fields) : value_fields);
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
  } else if (dimension == 3) {
    read_values3(reader, value, path, r);
  } else {
    read_values(reader, value, path, r);
  }
  return r;
}

// ---- Measuring one field of one pair

double distance(const Point2& a, const Point2& b) { return std::hypot(a.x - b.x, a.y - b.y); }
double distance(const Point3& a, const Point3& b) {
  return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
}

// The diagonal of the bounding box of cp ∪ tp: the scale of positions (see the header).
double pair_size(const PairSpec& pair) {
  Point2 low{infinity, infinity}, high{-infinity, -infinity};
  for (const auto* polygon : {&pair.cp, &pair.tp}) {
    for (const Point2& p : *polygon) {
      low = {std::min(low.x, p.x), std::min(low.y, p.y)};
      high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
  }
  return distance(low, high);
}

double pair_size(const Pair3Spec& pair) {
  Point3 low{infinity, infinity, infinity}, high{-infinity, -infinity, -infinity};
  for (const auto* block : {&pair.cp, &pair.tp}) {
    for (const Point3& p : block->vertices) {
      low = {std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z)};
      high = {std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z)};
    }
  }
  return distance(low, high);
}

template <class Point>
double directed_hausdorff(const std::vector<Point>& from, const std::vector<Point>& to) {
  double farthest = 0.0;
  for (const Point& p : from) {
    double nearest = infinity;
    for (const Point& q : to) nearest = std::min(nearest, distance(p, q));
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

ordered_json point_json(const Point2& p) { return ordered_json::array({p.x, p.y}); }
ordered_json point_json(const Point3& p) { return ordered_json::array({p.x, p.y, p.z}); }

template <class Point>
ordered_json points_json(const std::vector<Point>& vertices) {
  ordered_json out = ordered_json::array();
  for (const Point& p : vertices) out.push_back(point_json(p));
  return out;
}

ordered_json polyhedron_json(const PolyhedronSpec& block) {
  ordered_json out;
  out["vertices"] = points_json(block.vertices);
  out["faces"] = block.faces;
  return out;
}

// A 3D sub-value that is null when its parent object is: the depth of a penetration, the
// corners of a contact set.
template <class Parent, class Get>
std::optional<ordered_json> nested(bool given, const std::optional<Parent>& parent, Get get) {
  if (!given) return std::nullopt;
  if (!parent) return ordered_json(nullptr);
  return get(*parent);
}

template <class Value>
std::optional<ordered_json> json_if(const std::optional<Value>& value) {
  if (!value) return std::nullopt;
  if constexpr (std::is_same_v<Value, Point3>) {
    return point_json(*value);
  } else {
    return ordered_json(*value);
  }
}

// The value a result gives for `field`, as written in the output schema; nullopt when absent.
// A field is compared when theirs gives it.
std::optional<ordered_json> field_value(const ResultRecord& r, Field field) {
  switch (field) {
    case Field::result:
      return ordered_json(r.status ? to_string(*r.status) : std::string_view("present"));
    case Field::status:
      return r.status ? std::optional(ordered_json(to_string(*r.status))) : std::nullopt;
    case Field::ip_size:
      return r.ip ? std::optional(ordered_json(r.ip->size())) : std::nullopt;
    case Field::ip:
      return r.ip ? std::optional(points_json(*r.ip)) : std::nullopt;
    case Field::area:
      return json_if(r.area);
    case Field::force:
      return r.force ? std::optional(ordered_json::array({r.force->x, r.force->y})) : std::nullopt;
    case Field::point:
      if (!r.has_point) return std::nullopt;
      return r.point ? point_json(*r.point) : ordered_json(nullptr);
    case Field::volume:
      return json_if(r.volume);
    case Field::distance:
      return nested(r.has_distance, r.distance, [](double d) { return ordered_json(d); });
    case Field::depth:
      return nested(r.has_penetration && !(r.penetration && !r.penetration->depth), r.penetration,
                    [](const PenetrationRecord& p) { return ordered_json(*p.depth); });
    case Field::normal:
      return r.penetration ? json_if(r.penetration->normal) : std::nullopt;
    case Field::contact_dimension:
      return r.contact_set ? json_if(r.contact_set->dimension) : std::nullopt;
    case Field::contact_set:
      return nested(r.has_contact_set && !(r.contact_set && !r.contact_set->vertices),
                    r.contact_set,
                    [](const ContactSetRecord& s) { return points_json(*s.vertices); });
    case Field::constraints:
      return json_if(r.constraints);
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

// A count: equal or not; its error is the difference of the counts.
FieldCase count(std::size_t ours, std::size_t theirs) {
  FieldCase c = discrete(ours, theirs);
  c.abs_error = static_cast<double>(ours > theirs ? ours - theirs : theirs - ours);
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

// Two vertex sets (an IP, a contact set's corners): the symmetric Hausdorff distance relative
// to the pair's size.
template <class Point>
FieldCase measure_vertex_set(const std::vector<Point>& ours, const std::vector<Point>& theirs,
                             double size, const CompareOptions& options) {
  if (ours.empty() != theirs.empty()) return discrete(points_json(ours), points_json(theirs));
  const double error = std::max(directed_hausdorff(ours, theirs), directed_hausdorff(theirs, ours));
  return measured(error, size, options, points_json(ours), points_json(theirs));
}

FieldCase measure_point(const std::optional<Point2>& ours, const std::optional<Point2>& theirs,
                        double size, const CompareOptions& options) {
  if (!ours || !theirs) {
    return discrete(ours ? point_json(*ours) : nullptr, theirs ? point_json(*theirs) : nullptr);
  }
  return measured(distance(*ours, *theirs), size, options, point_json(*ours), point_json(*theirs));
}

// A number that may be null (a distance, a depth): null against a value is a presence
// difference, two values differ relative to |ours|.
FieldCase measure_nullable(const std::optional<double>& ours, const std::optional<double>& theirs,
                           const CompareOptions& options) {
  if (!ours || !theirs) {
    return discrete(ours ? ordered_json(*ours) : nullptr, theirs ? ordered_json(*theirs) : nullptr);
  }
  return measured(std::abs(*theirs - *ours), std::abs(*ours), options, *ours, *theirs);
}

// The angle between two non-zero directions, rad: atan2(|a x b|, a . b) keeps full relative
// accuracy for small angles (acos of a rounded cosine near 1 does not) and needs no
// normalisation, both terms scaling with |a| |b|.
double angle(const Point3& a, const Point3& b) {
  const double cx = a.y * b.z - a.z * b.y, cy = a.z * b.x - a.x * b.z, cz = a.x * b.y - a.y * b.x;
  return std::atan2(std::hypot(cx, cy, cz), a.x * b.x + a.y * b.y + a.z * b.z);
}

FieldCase measure_normal(const ResultRecord& ours, const Point3& theirs,
                         const CompareOptions& options) {
  if (!ours.penetration) return discrete(nullptr, point_json(theirs));
  const Point3 normal = ours.penetration->normal.value();
  return measured(angle(normal, theirs), 1.0, options, point_json(normal), point_json(theirs));
}

FieldCase measure_contact_set(const ResultRecord& ours, const ResultRecord& theirs, double size,
                              const CompareOptions& options) {
  if (!ours.contact_set || !theirs.contact_set) {
    return discrete(*field_value(ours, Field::contact_set),
                    *field_value(theirs, Field::contact_set));
  }
  return measure_vertex_set(ours.contact_set->vertices.value(), *theirs.contact_set->vertices, size,
                            options);
}

std::optional<double> depth(const ResultRecord& r) {
  return r.penetration ? r.penetration->depth : std::nullopt;
}

// `field` of two results that are not errors; `theirs` gives the field, ours (read from our
// output) gives every field of its dimension.
FieldCase measure(Field field, const ResultRecord& ours, const ResultRecord& theirs, double size,
                  const CompareOptions& options) {
  switch (field) {
    case Field::ip_size:
      return count(ours.ip.value().size(), theirs.ip->size());
    case Field::ip:
      return measure_vertex_set(ours.ip.value(), *theirs.ip, size, options);
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
    case Field::volume:
      return measured(std::abs(*theirs.volume - ours.volume.value()), std::abs(*ours.volume),
                      options, *ours.volume, *theirs.volume);
    case Field::distance:
      return measure_nullable(ours.distance, theirs.distance, options);
    case Field::depth:
      return measure_nullable(depth(ours), depth(theirs), options);
    case Field::normal:
      return measure_normal(ours, *theirs.penetration->normal, options);
    case Field::contact_dimension:
      return discrete(field_value(ours, field).value_or(nullptr), *field_value(theirs, field));
    case Field::contact_set:
      return measure_contact_set(ours, theirs, size, options);
    case Field::constraints:
      return count(ours.constraints.value(), *theirs.constraints);
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

  // Starts a pair: the cases added until the next start are its.
  void start(const PairSpec& pair) { start(pair.id, &pair, nullptr); }
  void start(const Pair3Spec& pair) { start(pair.id, nullptr, &pair); }

  void add(Field field, FieldCase c) {
    FieldReport& report = report_of(field);
    ++report.compared;
    if (c.abs_error) report.max_abs = std::max(report.max_abs.value_or(0.0), *c.abs_error);
    if (c.rel_error) report.max_rel = std::max(report.max_rel.value_or(0.0), *c.rel_error);
    if (c.disagrees) {
      ++report.disagreements;
      report.disagreeing_ids.push_back(*id_);
      pair_disagrees_ = true;
    }
    if (c.disagrees || c.abs_error.value_or(0.0) > 0.0) {
      if (pair2_) c.pair = *pair2_;
      if (pair3_) c.pair3 = *pair3_;
      report.worst.push_back(std::move(c));
    }
  }

  // Whether the pair just compared had a disagreement.
  bool pair_disagrees() const { return pair_disagrees_; }

 private:
  void start(const std::string& id, const PairSpec* pair2, const Pair3Spec* pair3) {
    id_ = &id;
    pair2_ = pair2;
    pair3_ = pair3;
    pair_disagrees_ = false;
  }

  FieldReport& report_of(Field field) {
    for (FieldReport& r : comparison_.fields) {
      if (r.field == field) return r;
    }
    throw std::invalid_argument("pairs compare: field " + std::string(to_string(field)) +
                                " is not compared in " + std::to_string(comparison_.dimension) +
                                "D");
  }

  Comparison& comparison_;
  const std::string* id_ = nullptr;
  const PairSpec* pair2_ = nullptr;
  const Pair3Spec* pair3_ = nullptr;
  bool pair_disagrees_ = false;
};

bool gives_values(const ResultRecord& r) {
  return r.ip || r.area || r.force || r.has_point || r.volume || r.has_distance ||
         r.has_penetration || r.has_contact_set || r.constraints;
}

// The pair started in `tally`: its presence, its verdict, and the values of `value_fields`
// that theirs gives.
void compare_pair(Tally& tally, std::span<const Field> value_fields, double size,
                  const ResultRecord& ours, const ResultRecord* theirs,
                  const CompareOptions& options) {
  if (!theirs) {
    tally.add(Field::result, discrete(*field_value(ours, Field::result), "missing"));
    return;
  }
  tally.add(Field::result, FieldCase{});
  const bool one_is_error =
      ours.status.value() == Verdict::error || theirs->status == Verdict::error;
  // The verdict when theirs gives one; and values without a status for blocks we refuse
  // disagree with the refusal, as a verdict (theirs shown as null).
  if (theirs->status || (one_is_error && gives_values(*theirs))) {
    tally.add(Field::status, discrete(*field_value(ours, Field::status),
                                      field_value(*theirs, Field::status).value_or(nullptr)));
  }
  if (one_is_error) return;  // one side computed nothing
  bool depth_disagrees = false;
  for (const Field field : value_fields) {
    if (!field_value(*theirs, field)) continue;
    if (field == Field::normal && depth_disagrees) continue;  // see the header
    FieldCase c = measure(field, ours, *theirs, size, options);
    if (field == Field::depth) depth_disagrees = c.disagrees;
    tally.add(field, std::move(c));
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
template <class Spec>
std::unordered_map<std::string, const ResultRecord*> index_theirs(const std::vector<Spec>& pairs,
                                                                  const std::string& input_source,
                                                                  const ResultsDocument& theirs) {
  std::unordered_map<std::string, bool> input_ids;
  for (const Spec& pair : pairs) input_ids.emplace(pair.id, true);
  std::unordered_map<std::string, const ResultRecord*> by_id;
  const JsonReader reader(theirs.source);
  for (const ResultRecord& r : theirs.results) {
    if (!input_ids.contains(r.id)) {
      reader.fail_expected(json_child(json_element("results", r.position), "id"),
                           "the id of a pair of " + input_source, json(r.id));
    }
    by_id.emplace(r.id, &r);
  }
  return by_id;
}

// Compares the results of `pairs` (the input's pairs of its dimension) into `c`.
template <class Spec>
void compare_all(Comparison& c, const std::vector<Spec>& pairs, const ResultsDocument& ours,
                 const ResultsDocument& theirs) {
  const auto by_id = index_theirs(pairs, c.input_source, theirs);
  const std::span<const Field> value_fields = compared_fields(c.dimension).subspan(2);
  Tally tally(c);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto found = by_id.find(pairs[i].id);
    tally.start(pairs[i]);
    compare_pair(tally, value_fields, pair_size(pairs[i]), ours.results.at(i),
                 found == by_id.end() ? nullptr : found->second, c.options);
    if (tally.pair_disagrees()) ++c.pairs_disagreeing;
  }
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

// The case's pair as in the input: its id, cp and tp.
ordered_json pair_json(const FieldCase& c, int dimension) {
  ordered_json out;
  if (dimension == 3) {
    out["id"] = c.pair3.id;
    out["cp"] = polyhedron_json(c.pair3.cp);
    out["tp"] = polyhedron_json(c.pair3.tp);
  } else {
    out["id"] = c.pair.id;
    out["cp"] = points_json(c.pair.cp);
    out["tp"] = points_json(c.pair.tp);
  }
  return out;
}

ordered_json case_json(const FieldCase& c, int dimension) {
  ordered_json out = pair_json(c, dimension);
  out["ours"] = c.ours;
  out["theirs"] = c.theirs;
  out["abs_error"] = error_json(c.abs_error);
  out["rel_error"] = error_json(c.rel_error);
  out["disagrees"] = c.disagrees;
  return out;
}

ordered_json field_json(const FieldReport& report, int dimension) {
  ordered_json worst = ordered_json::array();
  for (const FieldCase& c : report.worst) worst.push_back(case_json(c, dimension));
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
  out << "theirs " << c.theirs_source << " against ours (policy " << c.policy;
  if (c.dimension == 2) out << ", demarcation " << c.demarcation;
  out << ") on " << c.input_source << '\n';
  if (c.dimension == 3 && c.their_policy) {
    out << "theirs says: policy " << *c.their_policy << '\n';
  } else if (c.their_policy || c.their_demarcation) {
    out << "theirs says: policy " << c.their_policy.value_or("-") << ", demarcation "
        << c.their_demarcation.value_or("-") << '\n';
  }
  out << "a value disagrees when error > atol + rtol * scale; rtol "
      << tolerance_text(c.options.rtol) << ", atol " << tolerance_text(c.options.atol) << "\n\n";
}

void write_table(std::ostream& out, const Comparison& c) {
  int name_width = 10;  // wide enough for the 2D names; 3D has longer ones
  for (const FieldReport& r : c.fields) {
    name_width = std::max(name_width, static_cast<int>(to_string(r.field).size()) + 2);
  }
  out << std::left << std::setw(name_width) << "field" << std::setw(10) << "compared"
      << std::setw(10) << "disagree" << std::setw(14) << "max abs err"
      << "max rel err\n";
  for (const FieldReport& r : c.fields) {
    out << std::setw(name_width) << to_string(r.field) << std::setw(10) << r.compared
        << std::setw(10) << r.disagreements;
    if (r.compared == 0) {
      out << "not compared (absent from theirs)\n";
      continue;
    }
    out << std::setw(14) << error_text(r.max_abs) << error_text(r.max_rel) << '\n';
  }
  out << std::right;
}

void write_worst(std::ostream& out, const FieldReport& r, int dimension) {
  out << "\nworst " << to_string(r.field) << ": " << r.disagreements << " of " << r.compared
      << " disagree; " << r.worst.size() << " case" << (r.worst.size() == 1 ? "" : "s")
      << " shown\n";
  for (const FieldCase& c : r.worst) {
    const ordered_json pair = pair_json(c, dimension);
    out << "  " << pair["id"].get<std::string>() << ": ours " << c.ours.dump() << ", theirs "
        << c.theirs.dump();
    if (c.abs_error) out << "; error " << error_text(c.abs_error);
    if (c.rel_error) out << " (relative " << error_text(c.rel_error) << ')';
    out << (c.disagrees ? "  DISAGREES" : "  within tolerance") << '\n'
        << "    cp " << pair["cp"].dump() << "\n    tp " << pair["tp"].dump() << '\n';
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
  constexpr std::string_view names[] = {
      "result", "status",   "ip_size", "ip",     "area",
      "force",  "point",    "volume",  "distance", "depth",
      "normal", "contact_dimension", "contact_set", "constraints"};
  return names[static_cast<std::size_t>(field)];
}

std::span<const Field> compared_fields(int dimension) {
  if (dimension == 3) return fields3d;
  return fields2d;
}

const FieldReport& Comparison::field(Field f) const {
  for (const FieldReport& r : fields) {
    if (r.field == f) return r;
  }
  throw std::invalid_argument("pairs compare: field " + std::string(to_string(f)) +
                              " is not compared in " + std::to_string(dimension) + "D");
}

ResultsDocument parse_results(const json& document, const std::string& source_name,
                              int dimension) {
  if (dimension != 2 && dimension != 3) {
    throw std::invalid_argument("parse_results: dimension must be 2 or 3");
  }
  const JsonReader reader(source_name);
  reader.check_object(document, "", "a JSON object {\"results\", ...}",
                      dimension == 3 ? std::span<const JsonField>(document3_fields)
                                     : document_fields);
  ResultsDocument out;
  out.source = source_name;
  out.dimension = dimension;
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
    out.results.push_back(
        read_result(reader, results[i], json_element("results", i), i, dimension));
    ids.add(reader, "results", i, out.results.back().id);
  }
  return out;
}

ResultsDocument read_results_file(const std::filesystem::path& file, int dimension) {
  return parse_results(read_json_file(file), file.string(), dimension);
}

Comparison compare_results(const PairsInput& input, const ResultsDocument& ours,
                           const ResultsDocument& theirs, const CompareOptions& options) {
  if (ours.dimension != input.dimension || theirs.dimension != input.dimension) {
    throw std::invalid_argument("compare_results: the results documents were not read with the "
                                "input's dimension");
  }
  Comparison c;
  c.dimension = input.dimension;
  c.input_source = input.source;
  c.theirs_source = theirs.source;
  c.policy = ours.policy.value_or("-");
  c.demarcation = ours.demarcation.value_or("-");
  c.their_policy = theirs.policy;
  c.their_demarcation = theirs.demarcation;
  c.options = options;
  for (const Field field : compared_fields(c.dimension)) {
    c.fields.emplace_back().field = field;
  }
  if (c.dimension == 3) {
    c.pairs = input.pairs3.size();
    compare_all(c, input.pairs3, ours, theirs);
  } else {
    c.pairs = input.pairs.size();
    compare_all(c, input.pairs, ours, theirs);
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
  const ResultsDocument ours =
      parse_results(json(run_pairs(input, ours_overrides)), "ours", input.dimension);
  return compare_results(input, ours, theirs, options);
}

ordered_json comparison_json(const Comparison& c) {
  ordered_json out;
  out["dimension"] = c.dimension;
  out["input"] = c.input_source;
  out["theirs"] = c.theirs_source;
  out["policy"] = c.policy;
  if (c.dimension == 2) out["demarcation"] = c.demarcation;
  if (c.their_policy) out["their_policy"] = *c.their_policy;
  if (c.their_demarcation) out["their_demarcation"] = *c.their_demarcation;
  out["rtol"] = c.options.rtol;
  out["atol"] = c.options.atol;
  out["pairs"] = c.pairs;
  out["pairs_disagreeing"] = c.pairs_disagreeing;
  out["agree"] = c.agrees();
  ordered_json fields;
  for (const FieldReport& report : c.fields)
    fields[std::string(to_string(report.field))] = field_json(report, c.dimension);
  out["fields"] = std::move(fields);
  return out;
}

void write_comparison(std::ostream& out, const Comparison& comparison) {
  write_header(out, comparison);
  write_table(out, comparison);
  for (const FieldReport& report : comparison.fields) {
    if (!report.worst.empty()) write_worst(out, report, comparison.dimension);
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
