// libFuzzer target: the CDEM scene reader (dynamics/io/scene_cdem.hpp) and, on small scenes, the
// CDEM engine's construction (validation, meshing, the critical step, the initial ties) and its
// first steps.
//
// The bytes are the scene file. read_scene_cdem_file either returns a SceneCdem or throws
// InputError with a message "<file>: <path>: <problem>"; any other exception, a crash, a
// sanitizer report or a hang (libFuzzer's -timeout) is a failure. An accepted scene must hold
// what the format promises (check_accepted). The reader leaves the polygons and dt against the
// critical step to the engine, so a scene whose meshes are estimated at most max_elements
// elements then goes to Cdem: the constructor may refuse it with std::invalid_argument, whose
// message must start with the field ("time.dt: ...", "contact.kn: ...") or the block
// ("block 'a': ...") it names, or the two blocks that start inside each other ("block 'a' and
// block 'b' overlap by ..."). A built engine runs the scene's steps, but at most max_steps and,
// beyond min_steps, at most max_element_steps / elements of them (the small seeds touch within
// their first 170 steps); a step may stop with CdemStabilityError. Anything else fails, and so does a
// run whose report is inconsistent: time() other than steps() dt, an event outside [0, time()]
// or between unknown blocks, a block state that is not finite.
//
// The work bound comes before construction: the mesher accepts meshes of up to 5e6 elements
// (kernel::max_mesh_triangles), a benchmark rather than a fuzz case. estimated_elements bounds
// a mesh from the polygon alone: its area term is the mesher's own estimate (triangle_mesh.hpp,
// step 1: 2 area / (max_edge² √3/4)), which a thin part of the polygon exceeds by far, as
// refinement grades elements to the local feature size there. The boundary term adds, for every
// polygon edge, its length over min(max_edge, the distance from the edge to the nearest vertex
// not on it): a strip of length L and width w gets L / w, a needle of angle θ about 1 / θ, which
// is the order of the elements refinement puts into them. It overestimates a short edge s
// between long ones L (refinement grades away from it in O(log(L / s)) elements), so a polygon
// with an edge below about L / max_elements, or a vertex that close to another edge, is only
// read.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "json_target.hpp"
#include "rockcontact/dynamics/cdem.hpp"
#include "rockcontact/dynamics/io/scene_cdem.hpp"

namespace {

namespace rd = rockcontact::dynamics;
namespace rk = rockcontact::kernel;
namespace rf = rockcontact::fuzz;
constexpr const char* target = "fuzz_scene_cdem_json";
constexpr double max_elements = 2000.0;  // estimated, over all blocks
constexpr std::size_t max_vertices = 256;  // polygon vertices over all blocks (the estimate is O(n²))
constexpr std::size_t min_steps = 20;
constexpr std::size_t max_steps = 200;
constexpr std::size_t max_element_steps = 40'000;  // steps times elements, beyond min_steps

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

void check_params(const rd::CdemParams& p) {
  if (!finite_positive(p.dt)) rf::fail(target, "accepted a scene with dt not finite and > 0");
  if (!finite_positive(p.thickness)) rf::fail(target, "accepted a thickness not finite and > 0");
  if (!finite_non_negative(p.damping)) rf::fail(target, "accepted a damping not finite and >= 0");
  if (!std::isfinite(p.gravity[0]) || !std::isfinite(p.gravity[1])) rf::fail(target, "accepted a non-finite gravity");
  const rd::CdemContactParams& c = p.contact;
  if (!(finite_non_negative(c.friction_angle_deg) && c.friction_angle_deg < 90.0) ||
      !finite_non_negative(c.cohesion) || !finite_non_negative(c.tensile_strength) ||
      !finite_positive(c.search_tolerance)) {
    rf::fail(target, "accepted a contact parameter out of its range");
  }
  const bool penalty = c.law == rd::CdemLaw::penalty;
  if (penalty ? !(finite_positive(c.kn) && finite_positive(c.kt)) || c.subdivide : c.kn != 0.0 || c.kt != 0.0) {
    rf::fail(target, "accepted kn, kt or subdivide with the other law");
  }
}

void check_block(const rd::CdemBlockSpec& b) {
  if (b.id.empty()) rf::fail(target, "accepted a block without an id");
  if (b.vertices.size() < 3) rf::fail(target, "accepted a block of fewer than 3 vertices");
  for (const rk::Point2& v : b.vertices) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) rf::fail(target, "accepted a non-finite vertex");
  }
  const rd::CdemMaterial& m = b.material;
  if (!finite_positive(m.density) || !finite_positive(m.youngs_modulus) ||
      !(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    rf::fail(target, "accepted a material out of its range");
  }
  if (!finite_positive(b.max_edge)) rf::fail(target, "accepted a mesh.max_edge not finite and > 0");
  for (const double v : b.velocity) {
    if (!std::isfinite(v)) rf::fail(target, "accepted a non-finite velocity");
  }
  if (b.fixed && b.velocity != std::array<double, 3>{}) rf::fail(target, "accepted a fixed block with a velocity");
}

void check_accepted(const rd::SceneCdem& scene) {
  check_params(scene.params);
  if (!finite_positive(scene.duration)) rf::fail(target, "accepted a duration not finite and > 0");
  if (scene.every == 0) rf::fail(target, "accepted a scene recording every 0 steps");
  if (scene.blocks.empty()) rf::fail(target, "accepted a scene without blocks");
  for (std::size_t i = 0; i < scene.blocks.size(); ++i) {
    check_block(scene.blocks[i]);
    for (std::size_t j = 0; j < i; ++j) {
      if (scene.blocks[j].id == scene.blocks[i].id) rf::fail(target, "accepted two blocks with the same id");
    }
  }
  for (const std::string& id : scene.track) {
    const bool known = std::ranges::any_of(scene.blocks, [&](const rd::CdemBlockSpec& b) { return b.id == id; });
    if (!known) rf::fail(target, "accepted a scene tracking an unknown block");
  }
}

// Distance from p to the segment [a, b], m.
double distance_to_segment(rk::Point2 p, rk::Point2 a, rk::Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// The bound of the header comment for one block; +inf when it cannot be told (overflow).
// Degenerate polygons give 0 or +inf, both harmless: the mesher refuses them first.
double estimated_elements(const rd::CdemBlockSpec& b) {
  const std::vector<rk::Point2>& v = b.vertices;
  const std::size_t n = v.size();
  const double h = b.max_edge;
  double area2 = 0.0;  // twice the signed area
  for (std::size_t i = 0; i < n; ++i) {
    const rk::Point2 p = v[i], q = v[(i + 1) % n];
    area2 += p.x * q.y - p.y * q.x;
  }
  double estimate = std::abs(area2) / (h * h * (std::numbers::sqrt3 / 4.0));
  for (std::size_t i = 0; i < n; ++i) {
    const rk::Point2 a = v[i], b2 = v[(i + 1) % n];
    double nearest = h;
    for (std::size_t k = 0; k < n; ++k) {
      if (k == i || k == (i + 1) % n) continue;
      nearest = std::min(nearest, distance_to_segment(v[k], a, b2));
    }
    estimate += std::hypot(b2.x - a.x, b2.y - a.y) / nearest;
  }
  return std::isnan(estimate) ? std::numeric_limits<double>::infinity() : estimate;
}

bool small(const rd::SceneCdem& scene) {
  std::size_t vertices = 0;
  for (const rd::CdemBlockSpec& b : scene.blocks) vertices += b.vertices.size();
  if (vertices > max_vertices) return false;
  double elements = 0.0;
  for (const rd::CdemBlockSpec& b : scene.blocks) elements += estimated_elements(b);
  return elements <= max_elements;
}

// A refusal names what it refuses: a scene field, or a block by its id.
void check_refusal(const rd::SceneCdem& scene, const std::invalid_argument& e) {
  const std::string_view what = e.what();
  for (const std::string_view field :
       {"time.dt: ", "thickness: ", "damping: ", "gravity: ", "contact.", "blocks: "}) {
    if (what.starts_with(field)) return;
  }
  for (const rd::CdemBlockSpec& b : scene.blocks) {
    if (what.starts_with("block '" + b.id + "': ") && what.size() > b.id.size() + 10) return;
  }
  for (const rd::CdemBlockSpec& a : scene.blocks) {
    for (const rd::CdemBlockSpec& b : scene.blocks) {
      if (what.starts_with("block '" + a.id + "' and block '" + b.id + "' overlap by ")) return;
    }
  }
  rf::fail(target, "the engine refused the scene without naming a field or block: \"" + std::string(what) + "\"");
}

// What a run reports (the CLI's tracks, events and summary come from these).
void check_run(const rd::Cdem& sim, std::size_t steps, double dt) {
  if (sim.steps() != steps || sim.time() != static_cast<double>(steps) * dt) {
    rf::fail(target, "time() or steps() differ from the steps taken");
  }
  for (const rd::CdemEvent& e : sim.events()) {
    if (!(e.t >= 0.0 && e.t <= sim.time()) || e.block_a >= sim.block_count() || e.block_b >= sim.block_count() ||
        e.block_a == e.block_b) {
      rf::fail(target, "an event outside [0, time()] or between unknown blocks");
    }
  }
  for (std::size_t i = 0; i < sim.block_count(); ++i) {
    const rd::CdemBlockState s = sim.block_state(i);
    for (const double v : {s.centre[0], s.centre[1], s.velocity[0], s.velocity[1], s.rotation, s.omega}) {
      if (!std::isfinite(v)) rf::fail(target, "a block state that is not finite after a step without error");
    }
    (void)sim.mesh(i);
  }
  (void)sim.energies();
  (void)sim.momentum();
}

void run_engine(const rd::SceneCdem& scene) {
  std::optional<rd::Cdem> sim;
  try {
    sim.emplace(scene.blocks, scene.params);
  } catch (const std::invalid_argument& e) {  // a polygon, parameter or dt the engine refuses
    check_refusal(scene, e);
    return;
  }
  const std::size_t budget = std::max(min_steps, max_element_steps / std::max<std::size_t>(sim->element_count(), 1));
  const std::size_t steps = std::min({max_steps, budget, rd::step_count(scene)});
  try {
    for (std::size_t s = 0; s < steps; ++s) sim->step();
  } catch (const rd::CdemStabilityError&) {  // a non-finite state, energy growth, a deep node
    return;
  }
  check_run(*sim, steps, scene.params.dt);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rf::ScratchFile scratch("fuzz_scene_cdem_json");
  return rf::scene_input(
      target, scratch, {data, size}, [](const std::filesystem::path& file) { return rd::read_scene_cdem_file(file); },
      check_accepted, small, run_engine, "invalid_argument or CdemStabilityError");
}
