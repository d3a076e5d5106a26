#include "rockcontact/dynamics/io/checkpoint.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/io/atomic_file.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/version.hpp"

namespace rockcontact::dynamics {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

constexpr std::string_view format_name = "rockcontact-checkpoint";
constexpr std::int64_t format_version = 1;

std::string hex(std::uint64_t value) {
  std::array<char, 17> text{};
  const auto end = std::to_chars(text.data(), text.data() + 16, value, 16).ptr;
  const std::string digits(text.data(), end);
  return std::string(16 - digits.size(), '0') + digits;
}

template <std::size_t N>
ordered_json reals(const std::array<double, N>& values) {
  ordered_json out = ordered_json::array();
  for (const double x : values) out.push_back(x);
  return out;
}

ordered_json pair(double x, double y) { return ordered_json::array({x, y}); }

ordered_json energies(const Energies& e) {
  return {{"kinetic", e.kinetic},
          {"gravitational", e.gravitational},
          {"strain", e.strain},
          {"contact", e.contact},
          {"friction_dissipated", e.friction_dissipated},
          {"damping_dissipated", e.damping_dissipated}};
}

ordered_json spring_state(const contact::FrictionState& s) {
  return {{"displacement", pair(s.displacement.x, s.displacement.y)},
          {"sliding", s.sliding},
          {"force", pair(s.force.x, s.force.y)},
          {"normal", pair(s.normal.x, s.normal.y)}};
}

ordered_json engine(const Snapshot& s) {
  ordered_json blocks = ordered_json::array();
  for (const Snapshot::Block& b : s.blocks) {
    ordered_json vertices = ordered_json::array();
    for (const Point2& p : b.vertices) vertices.push_back(pair(p.x, p.y));
    blocks.push_back({{"vertices", std::move(vertices)},
                      {"rotation", b.rotation},
                      {"velocity", reals(b.velocity)},
                      {"stress", reals(b.stress)},
                      {"reference_centroid", pair(b.reference_centroid.x, b.reference_centroid.y)},
                      {"force", reals(b.force)},
                      {"contact_force", reals(b.contact_force)},
                      {"dashpot_force", reals(b.dashpot_force)},
                      {"acceleration", reals(b.acceleration)}});
  }
  ordered_json contacts = ordered_json::array();
  for (const ContactState& c : s.contacts) {
    contacts.push_back({{"cp", c.cp},
                        {"tp", c.tp},
                        {"cp_part", c.cp_part},
                        {"tp_part", c.tp_part},
                        {"point", pair(c.point.x, c.point.y)},
                        {"normal_force", pair(c.normal_force.x, c.normal_force.y)},
                        {"friction_force", pair(c.friction_force.x, c.friction_force.y)},
                        {"damping_force", pair(c.damping_force.x, c.damping_force.y)},
                        {"damping_moment", c.damping_moment},
                        {"sliding", c.sliding},
                        {"penetration", c.penetration}});
  }
  ordered_json springs = ordered_json::array();
  for (const Snapshot::Spring& p : s.springs) {
    springs.push_back({{"cp", p.cp},
                       {"tp", p.tp},
                       {"cp_part", p.cp_part},
                       {"tp_part", p.tp_part},
                       {"state", spring_state(p.state)}});
  }
  ordered_json relaxation = {{"moving", ordered_json::array()},
                             {"mass_scale", ordered_json::array()},
                             {"velocity", ordered_json::array()},
                             {"reference", s.relaxation.reference},
                             {"kinetic", s.relaxation.kinetic}};
  for (std::size_t i = 0; i < s.relaxation.moving.size(); ++i) {
    relaxation["moving"].push_back(s.relaxation.moving[i] != 0);
    relaxation["mass_scale"].push_back(s.relaxation.mass_scale[i]);
    relaxation["velocity"].push_back(reals(s.relaxation.velocity[i]));
  }
  const Equilibrium& e = s.equilibrium;
  return {{"time", s.time},
          {"steps", s.steps},
          {"blocks", std::move(blocks)},
          {"contacts", std::move(contacts)},
          {"springs", std::move(springs)},
          {"relaxation", std::move(relaxation)},
          {"contact_work", s.contact_work},
          {"friction_dissipated", s.friction_dissipated},
          {"mass_damping_dissipated", s.mass_damping_dissipated},
          {"dashpot_dissipated", s.dashpot_dissipated},
          {"initial_total", s.initial_total},
          {"initial_budget", s.initial_budget},
          {"max_gravitational", s.max_gravitational},
          {"max_penetration", s.max_penetration},
          {"equilibrium",
           {{"ran", e.ran},
            {"blocks", e.blocks},
            {"iterations", e.iterations},
            {"ratio", e.ratio},
            {"converged", e.converged},
            {"seconds", e.seconds},
            {"unsettled", e.unsettled}}},
          {"predicates",
           {{"calls", s.predicates.calls}, {"fallbacks", s.predicates.fallbacks}}}};
}

// Reads the members of a checkpoint, each failure an InputError at the member's JSON path.
class Reader {
 public:
  explicit Reader(std::string source) : json_(std::move(source)) {}

  const JsonReader& json_reader() const { return json_; }

  const json& member(const json& object, const std::string& path, std::string_view key) const {
    if (!object.is_object()) json_.fail_expected(path, "an object", object);
    const auto it = object.find(key);
    if (it == object.end()) json_.fail(json_child(path, key), "missing");
    return *it;
  }
  const json& array(const json& object, const std::string& path, std::string_view key) const {
    const json& value = member(object, path, key);
    if (!value.is_array()) json_.fail_expected(json_child(path, key), "an array", value);
    return value;
  }
  double real(const json& object, const std::string& path, std::string_view key) const {
    return json_.number(member(object, path, key), json_child(path, key), "a finite number");
  }
  std::uint64_t count(const json& object, const std::string& path, std::string_view key) const {
    const std::int64_t n = json_.integer(member(object, path, key), json_child(path, key),
                                         "an integer >= 0");
    if (n < 0) json_.fail_expected(json_child(path, key), "an integer >= 0", object.at(key));
    return static_cast<std::uint64_t>(n);
  }
  bool flag(const json& object, const std::string& path, std::string_view key) const {
    return json_.boolean(member(object, path, key), json_child(path, key), "true or false");
  }
  template <std::size_t N>
  std::array<double, N> reals(const json& object, const std::string& path,
                              std::string_view key) const {
    const std::vector<double> values =
        json_.numbers(member(object, path, key), json_child(path, key), N,
                      "an array of " + std::to_string(N) + " finite numbers");
    std::array<double, N> out{};
    std::copy(values.begin(), values.end(), out.begin());
    return out;
  }
  Point2 point(const json& object, const std::string& path, std::string_view key) const {
    const auto xy = reals<2>(object, path, key);
    return {xy[0], xy[1]};
  }
  Vector2 vector(const json& object, const std::string& path, std::string_view key) const {
    const auto xy = reals<2>(object, path, key);
    return {xy[0], xy[1]};
  }
  template <std::size_t N>
  std::array<std::uint64_t, N> counts(const json& object, const std::string& path,
                                      std::string_view key) const {
    const json& values = array(object, path, key);
    const std::string at = json_child(path, key);
    // A checkpoint written before a predicate kind was added has fewer counts: the missing
    // kinds were never counted, so they read as zero.
    if (values.empty() || values.size() > N) {
      json_.fail_expected(at, "an array of 1 to " + std::to_string(N) + " counts", values);
    }
    std::array<std::uint64_t, N> out{};
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::int64_t n = json_.integer(values[k], json_element(at, k), "an integer >= 0");
      if (n < 0) json_.fail_expected(json_element(at, k), "an integer >= 0", values[k]);
      out[k] = static_cast<std::uint64_t>(n);
    }
    return out;
  }

 private:
  JsonReader json_;
};

contact::FrictionState read_spring_state(const Reader& r, const json& value, const std::string& at) {
  contact::FrictionState s;
  s.displacement = r.vector(value, at, "displacement");
  s.sliding = r.flag(value, at, "sliding");
  s.force = r.vector(value, at, "force");
  s.normal = r.vector(value, at, "normal");
  return s;
}

Snapshot read_engine(const Reader& r, const json& value, const std::string& at) {
  Snapshot s;
  s.time = r.real(value, at, "time");
  s.steps = r.count(value, at, "steps");
  const json& blocks = r.array(value, at, "blocks");
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string path = json_element(json_child(at, "blocks"), i);
    Snapshot::Block& b = s.blocks.emplace_back();
    b.vertices = r.json_reader().polygon(r.member(blocks[i], path, "vertices"),
                                         json_child(path, "vertices"), "an array of [x, y]");
    b.rotation = r.real(blocks[i], path, "rotation");
    b.velocity = r.reals<6>(blocks[i], path, "velocity");
    b.stress = r.reals<3>(blocks[i], path, "stress");
    b.reference_centroid = r.point(blocks[i], path, "reference_centroid");
    b.force = r.reals<6>(blocks[i], path, "force");
    b.contact_force = r.reals<6>(blocks[i], path, "contact_force");
    b.dashpot_force = r.reals<6>(blocks[i], path, "dashpot_force");
    b.acceleration = r.reals<6>(blocks[i], path, "acceleration");
  }
  const json& contacts = r.array(value, at, "contacts");
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const std::string path = json_element(json_child(at, "contacts"), k);
    const json& c = contacts[k];
    ContactState& out = s.contacts.emplace_back();
    out.cp = r.count(c, path, "cp");
    out.tp = r.count(c, path, "tp");
    out.cp_part = r.count(c, path, "cp_part");
    out.tp_part = r.count(c, path, "tp_part");
    out.point = r.point(c, path, "point");
    out.normal_force = r.vector(c, path, "normal_force");
    out.friction_force = r.vector(c, path, "friction_force");
    out.damping_force = r.vector(c, path, "damping_force");
    out.damping_moment = r.real(c, path, "damping_moment");
    out.sliding = r.flag(c, path, "sliding");
    out.penetration = r.real(c, path, "penetration");
  }
  const json& springs = r.array(value, at, "springs");
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const std::string path = json_element(json_child(at, "springs"), k);
    const json& p = springs[k];
    s.springs.push_back({r.count(p, path, "cp"), r.count(p, path, "tp"),
                         r.count(p, path, "cp_part"), r.count(p, path, "tp_part"),
                         read_spring_state(r, r.member(p, path, "state"),
                                           json_child(path, "state"))});
  }
  const std::string relaxation_path = json_child(at, "relaxation");
  const json& relaxation = r.member(value, at, "relaxation");
  const json& moving = r.array(relaxation, relaxation_path, "moving");
  const json& scale = r.array(relaxation, relaxation_path, "mass_scale");
  const json& velocity = r.array(relaxation, relaxation_path, "velocity");
  if (scale.size() != moving.size() || velocity.size() != moving.size()) {
    r.json_reader().fail(relaxation_path, "expected \"moving\", \"mass_scale\" and \"velocity\" "
                                          "of the same length");
  }
  for (std::size_t i = 0; i < moving.size(); ++i) {
    s.relaxation.moving.push_back(r.json_reader().boolean(
        moving[i], json_element(json_child(relaxation_path, "moving"), i), "true or false"));
    s.relaxation.mass_scale.push_back(r.json_reader().non_negative(
        scale[i], json_element(json_child(relaxation_path, "mass_scale"), i), "a number >= 0"));
    const std::vector<double> v = r.json_reader().numbers(
        velocity[i], json_element(json_child(relaxation_path, "velocity"), i), 6,
        "an array of 6 finite numbers");
    std::copy(v.begin(), v.end(), s.relaxation.velocity.emplace_back().begin());
  }
  s.relaxation.reference = r.real(relaxation, relaxation_path, "reference");
  s.relaxation.kinetic = r.real(relaxation, relaxation_path, "kinetic");
  s.contact_work = r.real(value, at, "contact_work");
  s.friction_dissipated = r.real(value, at, "friction_dissipated");
  s.mass_damping_dissipated = r.real(value, at, "mass_damping_dissipated");
  s.dashpot_dissipated = r.real(value, at, "dashpot_dissipated");
  s.initial_total = r.real(value, at, "initial_total");
  s.initial_budget = r.real(value, at, "initial_budget");
  s.max_gravitational = r.real(value, at, "max_gravitational");
  s.max_penetration = r.real(value, at, "max_penetration");
  const std::string equilibrium_path = json_child(at, "equilibrium");
  const json& e = r.member(value, at, "equilibrium");
  s.equilibrium.ran = r.flag(e, equilibrium_path, "ran");
  s.equilibrium.blocks = r.count(e, equilibrium_path, "blocks");
  s.equilibrium.iterations = r.count(e, equilibrium_path, "iterations");
  s.equilibrium.ratio = r.real(e, equilibrium_path, "ratio");
  // A checkpoint written before these were kept has only the four above; its run's summary
  // then reports the pre-solve as not converged, in no measured time, with no unsettled blocks.
  if (e.contains("converged")) {
    s.equilibrium.converged = r.flag(e, equilibrium_path, "converged");
    s.equilibrium.seconds = r.real(e, equilibrium_path, "seconds");
    const json& unsettled = r.array(e, equilibrium_path, "unsettled");
    const std::string unsettled_path = json_child(equilibrium_path, "unsettled");
    for (std::size_t k = 0; k < unsettled.size(); ++k) {
      s.equilibrium.unsettled.push_back(
          r.json_reader().string(unsettled[k], json_element(unsettled_path, k), "a block id"));
    }
  }
  const std::string predicates_path = json_child(at, "predicates");
  const json& predicates = r.member(value, at, "predicates");
  s.predicates.calls = r.counts<kernel::predicate_kind_count>(predicates, predicates_path, "calls");
  s.predicates.fallbacks =
      r.counts<kernel::predicate_kind_count>(predicates, predicates_path, "fallbacks");
  return s;
}

}  // namespace

ordered_json checkpoint_json(const Scene& scene, const Checkpoint& checkpoint) {
  return {{"format", format_name},
          {"format_version", format_version},
          {"rockcontact", ROCKCONTACT_VERSION_STRING},
          {"scene", scene.source},
          {"scene_digest", hex(checkpoint.scene_digest)},
          {"steps", checkpoint.engine.steps},
          {"time", checkpoint.engine.time},
          {"initial_energy", energies(checkpoint.initial)},
          {"engine", engine(checkpoint.engine)}};
}

void write_checkpoint(const std::filesystem::path& file, const Scene& scene,
                      const Checkpoint& checkpoint) {
  AtomicFile out(file);
  out.stream() << checkpoint_json(scene, checkpoint).dump() << '\n';
  out.commit();
}

Checkpoint read_checkpoint(const std::filesystem::path& file, const Scene& scene) {
  const json document = read_json_file(file);
  const Reader r(file.string());
  const JsonReader& reader = r.json_reader();
  const json& format = r.member(document, "", "format");
  if (format != format_name) {
    reader.fail_expected("format", "\"rockcontact-checkpoint\" (a file that run --checkpoint-every "
                                   "wrote)", format);
  }
  if (r.count(document, "", "format_version") != format_version) {
    reader.fail("format_version", "expected " + std::to_string(format_version) + ", got " +
                                      describe_json(document.at("format_version")));
  }
  const std::string& version = reader.string(r.member(document, "", "rockcontact"), "rockcontact",
                                             "the version that wrote it");
  if (version != ROCKCONTACT_VERSION_STRING) {
    reader.fail("rockcontact", std::string("written by rockcontact ") + version + ", this is " +
                                   ROCKCONTACT_VERSION_STRING +
                                   ", which may step differently; expected a checkpoint written "
                                   "by this version");
  }
  const std::string& digest = reader.string(r.member(document, "", "scene_digest"), "scene_digest",
                                            "16 hex digits");
  if (digest != hex(scene.digest)) {
    reader.fail("scene_digest",
                "written for another scene (" + digest + ", " + scene.source + " is " +
                    hex(scene.digest) + "); expected a checkpoint of this scene (only its "
                    "\"description\", \"output\" and \"time.duration\" may differ)");
  }
  Checkpoint out;
  out.scene_digest = scene.digest;
  const json& initial = r.member(document, "", "initial_energy");
  Energies& e = out.initial;
  e.kinetic = r.real(initial, "initial_energy", "kinetic");
  e.gravitational = r.real(initial, "initial_energy", "gravitational");
  e.strain = r.real(initial, "initial_energy", "strain");
  e.contact = r.real(initial, "initial_energy", "contact");
  e.friction_dissipated = r.real(initial, "initial_energy", "friction_dissipated");
  e.damping_dissipated = r.real(initial, "initial_energy", "damping_dissipated");
  out.engine = read_engine(r, r.member(document, "", "engine"), "engine");
  return out;
}

}  // namespace rockcontact::dynamics
