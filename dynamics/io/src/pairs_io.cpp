#include "rockcontact/dynamics/io/pairs_io.hpp"

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

std::string join_message(const std::string& source, const std::string& path,
                         const std::string& problem) {
  return path.empty() ? source + ": " + problem : source + ": " + path + ": " + problem;
}

constexpr JsonField document_fields[] = {
    {"kn", true, "the normal penalty kn in Pa, a finite number > 0"},
    {"H", true, "the potential length scale H in m, a finite number > 0"},
    {"policy", false, "one of \"float\", \"filtered\", \"exact\", \"checked\""},
    {"demarcation", false, "one of \"paper\", \"exact\""},
    {"pairs", true, "an array of pairs {\"id\", \"cp\", \"tp\"}"},
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

std::vector<PairSpec> read_pair_list(const JsonReader& reader, const json& value) {
  const std::string path = "pairs";
  if (!value.is_array()) reader.fail_expected(path, expected(document_fields, "pairs"), value);
  std::vector<PairSpec> result;
  result.reserve(value.size());
  UniqueIds ids;
  for (std::size_t i = 0; i < value.size(); ++i) {
    result.push_back(read_pair(reader, value[i], json_element(path, i)));
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

ordered_json run_all(const contact::PotentialContactMethod& method, const PairsInput& input,
                     const contact::PotentialContactParams& params) {
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
    const auto error = evaluate(method, spec, i, params, workspace, result);
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
  const JsonReader reader(source_name);
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
  input.pairs = read_pair_list(reader, document.at("pairs"));
  return input;
}

PairsInput read_pairs_file(const std::filesystem::path& file) {
  return parse_pairs(read_json_file(file), file.string());
}

ordered_json run_pairs(const PairsInput& input, const PairsOverrides& overrides) {
  const kernel::PolicyKind policy = overrides.policy.value_or(input.policy);
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
