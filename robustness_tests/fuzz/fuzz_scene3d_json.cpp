// libFuzzer target: the 3D scene reader (dynamics/io/scene3d.hpp) and, on small scenes, the
// implicit 3D DDA's construction (validation, detection, the initial equilibrium) and its first
// steps.
//
// The bytes are the scene file. read_scene3d_file either returns a Scene3d or throws InputError
// with a message "<file>: <path>: <problem>"; any other exception, a crash, a sanitizer report or
// a hang (libFuzzer's -timeout) is a failure. An accepted scene must hold what the format
// promises: dt and duration finite and > 0, every block with at least one part (each a valid
// ConvexPolyhedron by construction), tracked ids among the blocks, `every` >= 1. A scene of at
// most max_blocks blocks and max_vertices vertices in all then goes to the engine: the
// constructor may refuse it (std::invalid_argument naming the field, Stability3dError for an
// initial equilibrium the blocks do not have), and up to three steps may stop with
// Stability3dError; anything else fails. Larger scenes are only read: a run of theirs is a
// benchmark, not a fuzz case. Regions cut by joint sets are bounded by the cut's own limits
// (kernel/3d/block_cutting.hpp) before the engine sees them.

#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>

#include "json_target.hpp"
#include "rockcontact/dynamics/dda3d.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"

namespace {

namespace rd = rockcontact::dynamics;
namespace rf = rockcontact::fuzz;
constexpr const char* target = "fuzz_scene3d_json";
constexpr std::size_t max_blocks = 6;
constexpr std::size_t max_vertices = 64;

void check_accepted(const rd::Scene3d& scene) {
  if (!(std::isfinite(scene.params.dt) && scene.params.dt > 0.0) ||
      !(std::isfinite(scene.duration) && scene.duration > 0.0)) {
    rf::fail(target, "accepted a scene with dt or duration not finite and > 0");
  }
  if (scene.every == 0) rf::fail(target, "accepted a scene recording every 0 steps");
  for (const rd::Block3dSpec& b : scene.blocks) {
    if (b.parts.empty()) rf::fail(target, "accepted a block without parts");
  }
  for (const std::string& id : scene.track) {
    bool known = false;
    for (const rd::Block3dSpec& b : scene.blocks) known = known || b.id == id;
    if (!known) rf::fail(target, "accepted a scene tracking an unknown block");
  }
}

bool small(const rd::Scene3d& scene) {
  if (scene.blocks.size() > max_blocks) return false;
  std::size_t vertices = 0;
  for (const rd::Block3dSpec& b : scene.blocks) {
    for (const auto& part : b.parts) vertices += part.size();
  }
  return vertices <= max_vertices;
}

void run_engine(const rd::Scene3d& scene) {
  try {
    rd::Dda3d sim(scene.blocks, scene.law, scene.params);
    for (int step = 0; step < 3; ++step) sim.step();
  } catch (const std::invalid_argument&) {  // a block, law or parameter the engine refuses
  } catch (const rd::Stability3dError&) {   // no initial equilibrium, or a step it cannot take
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rf::ScratchFile scratch("fuzz_scene3d_json");
  return rf::scene_input(
      target, scratch, {data, size}, [](const std::filesystem::path& file) { return rd::read_scene3d_file(file); },
      check_accepted, small, run_engine, "invalid_argument or Stability3dError");
}
