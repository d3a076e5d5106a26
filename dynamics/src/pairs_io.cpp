#include "rockcontact/dynamics/pairs_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "rockcontact/contact/potential_contact.hpp"
#include "rockcontact/kernel/convex_polygon.hpp"
#include "rockcontact/kernel/entrance_block.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

std::string join_message(const std::string& source, const std::string& path,
                         const std::string& problem) {
  return path.empty() ? source + ": " + problem : source + ": " + path + ": " + problem;
}

// "got ..." for messages: the JSON type and the value, cut short when long.
std::string describe(const json& value) {
  constexpr std::size_t max_shown = 40;
  if (value.is_null()) return "null";
  // A document built in memory may hold NaN or infinity, which dump() would print as null.
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    return "non-finite number " + std::to_string(value.get<double>());
  }
  std::string text = value.dump();
  if (text.size() > max_shown) text = text.substr(0, max_shown) + "...";
  return std::string(value.type_name()) + " " + text;
}

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

// One field of an object: its name, whether it must be present, and what it must hold (the
// "expected ..." of every message about it).
struct Field {
  std::string_view name;
  bool required;
  std::string_view expected;
};

constexpr Field document_fields[] = {
    {"kn", true, "the normal penalty kn in Pa, a finite number > 0"},
    {"H", true, "the potential length scale H in m, a finite number > 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\""},
    {"demarcation", false, "one of \"paper\", \"exact\""},
    {"pairs", true, "an array of pairs {\"id\", \"cp\", \"tp\"}"},
};
constexpr Field pair_fields[] = {
    {"id", true, "a string, unique within the file"},
    {"cp", true, "the contact polygon, an array of [x, y] vertices"},
    {"tp", true, "the target polygon, an array of [x, y] vertices"},
};

const Field& field(std::span<const Field> fields, std::string_view name) {
  return *std::find_if(fields.begin(), fields.end(),
                       [&](const Field& f) { return f.name == name; });
}

// One document being parsed: knows its source name for every message.
class Parser {
 public:
  explicit Parser(const std::string& source) : source_(source) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw InputError(source_, path, problem);
  }

  [[noreturn]] void fail_expected(const std::string& path, std::string_view expected,
                                  const json& got) const {
    fail(path, "expected " + std::string(expected) + ", got " + describe(got));
  }

  // Checks that `value` is an object whose fields are all in `fields`, with the required ones.
  void check_object(const json& value, const std::string& path, std::string_view expected,
                    std::span<const Field> fields) const {
    if (!value.is_object()) fail_expected(path, expected, value);
    std::string names;
    for (const Field& f : fields) names += (names.empty() ? "" : ", ") + std::string(f.name);
    for (const auto& [key, item] : value.items()) {
      const bool known =
          std::any_of(fields.begin(), fields.end(), [&](const Field& f) { return f.name == key; });
      if (!known) fail(child(path, key), "unknown field; expected only " + names);
    }
    for (const Field& f : fields) {
      if (f.required && !value.contains(f.name)) {
        fail(child(path, f.name), "missing field; expected " + std::string(f.expected));
      }
    }
  }

  double positive(const json& value, const std::string& path, const Field& f) const {
    if (!value.is_number() || !std::isfinite(value.get<double>()) || !(value.get<double>() > 0.0)) {
      fail_expected(path, f.expected, value);
    }
    return value.get<double>();
  }

  template <class Choice>
  Choice choice(const json& value, const std::string& path, const Field& f,
                std::optional<Choice> (*parse)(std::string_view)) const {
    if (value.is_string()) {
      if (const auto parsed = parse(value.get_ref<const std::string&>())) return *parsed;
    }
    fail_expected(path, f.expected, value);
  }

  std::vector<kernel::Point2> polygon(const json& value, const std::string& path,
                                      const Field& f) const {
    if (!value.is_array()) fail_expected(path, f.expected, value);
    std::vector<kernel::Point2> vertices;
    vertices.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      const json& v = value[i];
      if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
        fail_expected(element(path, i), "a vertex, an [x, y] pair of numbers", v);
      }
      vertices.push_back({v[0].get<double>(), v[1].get<double>()});
    }
    return vertices;
  }

  PairSpec pair(const json& value, const std::string& path) const {
    check_object(value, path, "a pair, an object {\"id\", \"cp\", \"tp\"}", pair_fields);
    const json& id = value.at("id");
    if (!id.is_string()) fail_expected(child(path, "id"), field(pair_fields, "id").expected, id);
    return {id.get<std::string>(),
            polygon(value.at("cp"), child(path, "cp"), field(pair_fields, "cp")),
            polygon(value.at("tp"), child(path, "tp"), field(pair_fields, "tp"))};
  }

  std::vector<PairSpec> pairs(const json& value) const {
    const std::string path = "pairs";
    if (!value.is_array()) fail_expected(path, field(document_fields, "pairs").expected, value);
    std::vector<PairSpec> result;
    result.reserve(value.size());
    std::unordered_map<std::string, std::size_t> first_index;
    for (std::size_t i = 0; i < value.size(); ++i) {
      result.push_back(pair(value[i], element(path, i)));
      const auto [it, inserted] = first_index.emplace(result.back().id, i);
      if (!inserted) {
        fail(child(element(path, i), "id"), "duplicate id \"" + result.back().id + "\" (also " +
                                                element(path, it->second) +
                                                ".id); expected ids unique within the file");
      }
    }
    return result;
  }

 private:
  const std::string& source_;
};

// Evaluates one pair into `result`, or returns the kernel's message for an invalid polygon.
template <kernel::NumberPolicy Policy>
std::optional<std::string> evaluate(const PairSpec& spec, std::size_t index,
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
    contact::evaluate_pair<Policy>(cp, tp, params, workspace, result);
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

template <kernel::NumberPolicy Policy>
ordered_json run_all(const PairsInput& input, const contact::PotentialContactParams& params) {
  using clock = std::chrono::steady_clock;
  ordered_json results = ordered_json::array();
  contact::PairWorkspace workspace;
  contact::PairResult result;
  clock::duration elapsed{};
  std::uint64_t predicates = 0;
  std::uint64_t fallbacks = 0;
  for (std::size_t i = 0; i < input.pairs.size(); ++i) {
    const PairSpec& spec = input.pairs[i];
    const auto start = clock::now();
    const auto error = evaluate<Policy>(spec, i, params, workspace, result);
    elapsed += clock::now() - start;
    if (error) {
      results.push_back({{"id", spec.id}, {"status", "error"}, {"error", *error}});
      continue;
    }
    predicates += result.predicates;
    fallbacks += result.fallbacks;
    results.push_back(result_json(spec.id, result));
  }
  ordered_json stats;
  stats["pairs"] = input.pairs.size();
  stats["predicates"] = predicates;
  stats["fallbacks"] = fallbacks;
  stats["seconds"] = std::chrono::duration<double>(elapsed).count();
  ordered_json out;
  out["results"] = std::move(results);
  out["stats"] = std::move(stats);
  return out;
}

}  // namespace

InputError::InputError(std::string source, std::string path, const std::string& problem)
    : std::runtime_error(join_message(source, path, problem)),
      source_(std::move(source)),
      path_(std::move(path)) {}

PairsInput parse_pairs(const json& document, const std::string& source_name) {
  const Parser parser(source_name);
  parser.check_object(document, "", "a JSON object {\"kn\", \"H\", \"pairs\", ...}",
                      document_fields);
  PairsInput input;
  input.source = source_name;
  input.kn = parser.positive(document.at("kn"), "kn", field(document_fields, "kn"));
  input.H = parser.positive(document.at("H"), "H", field(document_fields, "H"));
  if (document.contains("policy")) {
    input.policy = parser.choice(document.at("policy"), "policy", field(document_fields, "policy"),
                                 &kernel::parse_policy);
  }
  if (document.contains("demarcation")) {
    input.demarcation =
        parser.choice(document.at("demarcation"), "demarcation",
                      field(document_fields, "demarcation"), &kernel::parse_demarcation);
  }
  input.pairs = parser.pairs(document.at("pairs"));
  return input;
}

PairsInput read_pairs_file(const std::filesystem::path& file) {
  const std::string source = file.string();
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(source, "", "cannot open the file for reading");
  json document;
  try {
    document = json::parse(stream);
  } catch (const json::exception& e) {
    // nlohmann's messages start with "[json.exception.<kind>.<id>] "; the rest carries the
    // line and column of a syntax error.
    const std::string_view what = e.what();
    const auto end_of_tag = what.find("] ");
    const auto detail = end_of_tag == std::string_view::npos ? what : what.substr(end_of_tag + 2);
    throw InputError(source, "", "malformed JSON: " + std::string(detail));
  }
  return parse_pairs(document, source);
}

ordered_json run_pairs(const PairsInput& input, const PairsOverrides& overrides) {
  const kernel::PolicyKind policy = overrides.policy.value_or(input.policy);
  contact::PotentialContactParams params = contact::default_potential_contact_params();
  params.kn = input.kn;
  params.H = input.H;
  params.demarcation = overrides.demarcation.value_or(input.demarcation);
  ordered_json body =
      kernel::with_policy(policy, [&](auto tag) { return run_all<decltype(tag)>(input, params); });
  ordered_json out;
  out["policy"] = kernel::to_string(policy);
  out["demarcation"] = kernel::to_string(params.demarcation);
  out["results"] = std::move(body["results"]);
  out["stats"] = std::move(body["stats"]);
  return out;
}

}  // namespace rockcontact::dynamics
