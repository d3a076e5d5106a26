#include "rockcontact/dynamics/io/pairs_io.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "rockcontact/contact/generalized3d/pair_contact3d.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// A field name or id from the document may hold any character, NUL included; the message shows
// control characters as JSON escapes so that it stays one readable C string.
std::string printable(const std::string& text) {
  std::string shown;
  shown.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      shown += c;
      continue;
    }
    char escape[7];
    std::snprintf(escape, sizeof escape, "\\u%04x", byte);
    shown += escape;
  }
  return shown;
}

std::string join_message(const std::string& source, const std::string& path,
                         const std::string& problem) {
  return path.empty() ? source + ": " + problem : source + ": " + path + ": " + problem;
}

constexpr JsonField document_fields[] = {
    {"dimension", false, "2 (polygon pairs, the default) or 3 (polyhedron pairs)"},
    {"kn", true, "the normal penalty kn in Pa, a finite number > 0"},
    {"H", true, "the potential length scale H in m, a finite number > 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"demarcation", false, "one of \"paper\", \"exact\""},
    {"pairs", true, "an array of pairs {\"id\", \"cp\", \"tp\"}"},
};
constexpr JsonField document3_fields[] = {
    {"dimension", true, "3"},
    {"kn", true, "the normal penalty kn in N/m per constraint, a finite number > 0"},
    {"tolerance", false, "the distance in m below which separate pairs get constraints, a finite number >= 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"pairs", true, "an array of pairs {\"id\", \"cp\", \"tp\"}"},
};
constexpr JsonField pair3_fields[] = {
    {"id", true, "a string, unique within the file"},
    {"cp", true, "the contact block, a convex polyhedron {\"vertices\", \"faces\"}"},
    {"tp", true, "the target block, a convex polyhedron {\"vertices\", \"faces\"}"},
};
constexpr JsonField pair_fields[] = {
    {"id", true, "a string, unique within the file"},
    {"cp", true, "the contact polygon, an array of [x, y] vertices"},
    {"tp", true, "the target polygon, an array of [x, y] vertices"},
};

std::string_view expected(std::span<const JsonField> fields, std::string_view name) {
  return json_field(fields, name).expected;
}

PairSpec read_pair(const JsonReader& reader, const json& value, const std::string& path) {
  reader.check_object(value, path, "a pair, an object {\"id\", \"cp\", \"tp\"}", pair_fields);
  return {reader.string(value.at("id"), json_child(path, "id"), expected(pair_fields, "id")),
          reader.polygon(value.at("cp"), json_child(path, "cp"), expected(pair_fields, "cp")),
          reader.polygon(value.at("tp"), json_child(path, "tp"), expected(pair_fields, "tp"))};
}

Pair3Spec read_pair3(const JsonReader& reader, const json& value, const std::string& path) {
  reader.check_object(value, path, "a pair, an object {\"id\", \"cp\", \"tp\"}", pair3_fields);
  return {reader.string(value.at("id"), json_child(path, "id"), expected(pair3_fields, "id")),
          reader.polyhedron(value.at("cp"), json_child(path, "cp"), expected(pair3_fields, "cp")),
          reader.polyhedron(value.at("tp"), json_child(path, "tp"), expected(pair3_fields, "tp"))};
}

template <class Spec, class Read>
std::vector<Spec> read_pair_list(const JsonReader& reader, const json& value, Read read) {
  const std::string path = "pairs";
  if (!value.is_array()) reader.fail_expected(path, expected(document_fields, "pairs"), value);
  std::vector<Spec> result;
  result.reserve(value.size());
  UniqueIds ids;
  for (std::size_t i = 0; i < value.size(); ++i) {
    result.push_back(read(reader, value[i], json_element(path, i)));
    ids.add(reader, path, i, result.back().id);
  }
  return result;
}

// Evaluates one pair into `result`, or returns the kernel's message for an invalid polygon.
std::optional<std::string> evaluate(const contact::PotentialContactMethod& method,
                                    const PairSpec& spec, std::size_t index,
                                    const contact::PotentialContactParams& params,
                                    contact::PairWorkspace& workspace,
                                    contact::PairResult& result) {
  const std::string name = "pairs[" + std::to_string(index) + "]";
  const std::string id = " (id '" + spec.id + "')";
  try {
    const auto cp =
        kernel::ConvexPolygon::make(name + ".cp" + id, spec.cp, kernel::VertexOrder::require_ccw);
    const auto tp =
        kernel::ConvexPolygon::make(name + ".tp" + id, spec.tp, kernel::VertexOrder::require_ccw);
    method.evaluate(cp, tp, params, workspace, result);
  } catch (const kernel::InvalidPolygon& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

ordered_json point_json(const kernel::Point2& p) { return ordered_json::array({p.x, p.y}); }

ordered_json result_json(const std::string& id, const contact::PairResult& r) {
  ordered_json ip = ordered_json::array();
  for (const auto& p : r.ip) ip.push_back(point_json(p));
  ordered_json out;
  out["id"] = id;
  out["status"] = kernel::to_string(r.status);
  out["ip"] = std::move(ip);
  out["area"] = r.area;
  out["force"] = ordered_json::array({r.force.x, r.force.y});
  out["point"] = r.point ? point_json(*r.point) : ordered_json(nullptr);
  out["fallbacks"] = r.fallbacks;
  return out;
}

ordered_json point3_json(const kernel::Point3& p) { return ordered_json::array({p.x, p.y, p.z}); }

ordered_json constraint_json(const kernel::ContactConstraint& c, double kn) {
  ordered_json out;
  out["type"] = contact::to_string(c.type);
  out["point_cp"] = point3_json(c.point_cp);
  out["point_tp"] = point3_json(c.point_tp);
  out["normal"] = point3_json(c.normal);
  out["gap"] = c.gap;
  out["force"] = point3_json(contact::penalty_force(c, kn));
  return out;
}

ordered_json result3_json(const std::string& id, const contact::Pair3dResult& r, double kn) {
  ordered_json out;
  out["id"] = id;
  out["status"] = kernel::to_string(r.status);
  out["volume"] = r.volume;
  out["distance"] = r.separation ? ordered_json(r.separation->distance) : ordered_json(nullptr);
  if (r.penetration) {
    out["penetration"] = {{"depth", r.penetration->depth}, {"normal", point3_json(r.penetration->normal)}};
  } else {
    out["penetration"] = nullptr;
  }
  if (r.contact_set) {
    ordered_json corners = ordered_json::array();
    for (const auto& p : r.contact_set->vertices) corners.push_back(point3_json(p));
    out["contact_set"] = {{"dimension", r.contact_set->dimension}, {"vertices", std::move(corners)}};
  } else {
    out["contact_set"] = nullptr;
  }
  ordered_json constraints = ordered_json::array();
  for (const auto& c : r.constraints) constraints.push_back(constraint_json(c, kn));
  out["constraints"] = std::move(constraints);
  out["fallbacks"] = r.fallbacks;
  return out;
}

kernel::ConvexPolyhedron make_polyhedron(const std::string& name, const PolyhedronSpec& spec) {
  return kernel::ConvexPolyhedron::make(name, spec.vertices, spec.faces);
}

// The output document's results and stats: `evaluate(i, results)` appends pair i's result (or
// its error) and returns its predicate and fallback counts; only its time is measured.
template <class Evaluate>
ordered_json run_timed(std::size_t pairs, Evaluate evaluate) {
  using clock = std::chrono::steady_clock;
  ordered_json results = ordered_json::array();
  clock::duration elapsed{};
  std::uint64_t predicates = 0;
  std::uint64_t fallbacks = 0;
  for (std::size_t i = 0; i < pairs; ++i) {
    const auto start = clock::now();
    const auto [p, f] = evaluate(i, results);
    elapsed += clock::now() - start;
    predicates += p;
    fallbacks += f;
  }
  ordered_json stats;
  stats["pairs"] = pairs;
  stats["predicates"] = predicates;
  stats["fallbacks"] = fallbacks;
  stats["seconds"] = std::chrono::duration<double>(elapsed).count();
  ordered_json out;
  out["results"] = std::move(results);
  out["stats"] = std::move(stats);
  return out;
}

ordered_json run_all3(const PairsInput& input, kernel::PolicyKind policy) {
  contact::Pair3dParams params;
  params.kn = input.kn;
  params.tolerance = input.tolerance;
  contact::check_params(params);
  contact::Pair3dResult result;
  return run_timed(input.pairs3.size(), [&](std::size_t i, ordered_json& results) {
    const Pair3Spec& spec = input.pairs3[i];
    const std::string name = "pairs[" + std::to_string(i) + "]", id = " (id '" + spec.id + "')";
    try {
      const auto cp = make_polyhedron(name + ".cp" + id, spec.cp);
      const auto tp = make_polyhedron(name + ".tp" + id, spec.tp);
      kernel::with_policy(policy, [&](auto p) { contact::evaluate_pair3d<decltype(p)>(cp, tp, params, result); });
    } catch (const kernel::InvalidPolyhedron& e) {
      results.push_back({{"id", spec.id}, {"status", "error"}, {"error", e.what()}});
      return std::pair<std::uint64_t, std::uint64_t>{0, 0};
    }
    results.push_back(result3_json(spec.id, result, input.kn));
    return std::pair{result.predicates, result.fallbacks};
  });
}

ordered_json run_all(const contact::PotentialContactMethod& method, const PairsInput& input,
                     const contact::PotentialContactParams& params) {
  contact::PairWorkspace workspace;
  contact::PairResult result;
  return run_timed(input.pairs.size(), [&](std::size_t i, ordered_json& results) {
    const PairSpec& spec = input.pairs[i];
    if (const auto error = evaluate(method, spec, i, params, workspace, result)) {
      results.push_back({{"id", spec.id}, {"status", "error"}, {"error", *error}});
      return std::pair<std::uint64_t, std::uint64_t>{0, 0};
    }
    results.push_back(result_json(spec.id, result));
    return std::pair{result.predicates, result.fallbacks};
  });
}

}  // namespace

InputError::InputError(std::string source, std::string path, const std::string& problem)
    : std::runtime_error(join_message(source, printable(path), printable(problem))),
      source_(std::move(source)),
      path_(printable(path)) {}

namespace {

PairsInput parse_pairs3(const JsonReader& reader, const json& document) {
  reader.check_object(document, "", "a JSON object {\"dimension\": 3, \"kn\", \"pairs\", ...}", document3_fields);
  PairsInput input;
  input.source = reader.source();
  input.dimension = 3;
  input.kn = reader.positive(document.at("kn"), "kn", expected(document3_fields, "kn"));
  if (document.contains("tolerance")) {
    input.tolerance =
        reader.non_negative(document.at("tolerance"), "tolerance", expected(document3_fields, "tolerance"));
  }
  if (document.contains("policy")) {
    input.policy = reader.choice(document.at("policy"), "policy", expected(document3_fields, "policy"),
                                 &kernel::parse_policy);
  }
  input.pairs3 = read_pair_list<Pair3Spec>(reader, document.at("pairs"), read_pair3);
  return input;
}

}  // namespace

PairsInput parse_pairs(const json& document, const std::string& source_name) {
  const JsonReader reader(source_name);
  if (document.is_object() && document.contains("dimension")) {
    const json& dimension = document.at("dimension");
    if (dimension == 3) return parse_pairs3(reader, document);
    if (dimension != 2) reader.fail_expected("dimension", expected(document_fields, "dimension"), dimension);
  }
  reader.check_object(document, "", "a JSON object {\"kn\", \"H\", \"pairs\", ...}",
                      document_fields);
  PairsInput input;
  input.source = source_name;
  input.kn = reader.positive(document.at("kn"), "kn", expected(document_fields, "kn"));
  input.H = reader.positive(document.at("H"), "H", expected(document_fields, "H"));
  if (document.contains("policy")) {
    input.policy = reader.choice(document.at("policy"), "policy",
                                 expected(document_fields, "policy"), &kernel::parse_policy);
  }
  if (document.contains("demarcation")) {
    input.demarcation =
        reader.choice(document.at("demarcation"), "demarcation",
                      expected(document_fields, "demarcation"), &kernel::parse_demarcation);
  }
  input.pairs = read_pair_list<PairSpec>(reader, document.at("pairs"), read_pair);
  return input;
}

PairsInput read_pairs_file(const std::filesystem::path& file) {
  return parse_pairs(read_json_file(file), file.string());
}

ordered_json run_pairs(const PairsInput& input, const PairsOverrides& overrides) {
  const kernel::PolicyKind policy = overrides.policy.value_or(input.policy);
  if (input.dimension == 3) {
    if (overrides.demarcation) {
      throw InputError(input.source, "", "demarcation applies to 2D pairs; this file has \"dimension\": 3");
    }
    ordered_json body = run_all3(input, policy);
    ordered_json out;
    out["policy"] = kernel::to_string(policy);
    out["results"] = std::move(body["results"]);
    out["stats"] = std::move(body["stats"]);
    return out;
  }
  contact::PotentialContactParams params = contact::default_potential_contact_params();
  params.kn = input.kn;
  params.H = input.H;
  params.demarcation = overrides.demarcation.value_or(input.demarcation);
  contact::check_params(params);
  ordered_json body = run_all(contact::PotentialContactMethod(policy), input, params);
  ordered_json out;
  out["policy"] = kernel::to_string(policy);
  out["demarcation"] = kernel::to_string(params.demarcation);
  out["results"] = std::move(body["results"]);
  out["stats"] = std::move(body["stats"]);
  return out;
}

}  // namespace rockcontact::dynamics
