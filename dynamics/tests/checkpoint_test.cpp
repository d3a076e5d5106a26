#define BOOST_TEST_MODULE dynamics_checkpoint
#include <boost/test/unit_test.hpp>

// Checkpoint and restart (checkpoint.hpp): a run resumed from a checkpoint writes, from the
// checkpoint's instant on, the same bytes as the run that was never interrupted. The reference
// is that uninterrupted run itself, so any state the checkpoint loses (a friction spring's
// stretch, a dashpot's force, the energy bookkeeping, the relaxation of a static analysis)
// shows as a differing digit. The scene exercises all of it: a deformable stack settled by the
// pre-solve, a non-convex rigid block thrown into it, a triangle sliding on the floor under
// elastoplastic friction, contact dashpots and mass damping.

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/checkpoint.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/dynamics/io/scene_output.hpp"

namespace {

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;
using nlohmann::json;

json busy_scene() {
  return json::parse(R"({"dimension": 2,
   "time": {"dt": 1e-4, "duration": 0.06},
   "damping": 0.5,
   "materials": {"rock": {"density": 2500, "youngs_modulus": 5e9, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e9, "H": 0.5, "kt": 5e8, "friction_angle_deg": 20,
               "damping_ratio": 0.05},
   "blocks": [{"id": "floor", "material": "rock", "vertices": [[-1,-1],[7,-1],[7,0],[-1,0]],
               "fixed": true},
              {"id": "low", "material": "rock", "vertices": [[0,0],[1,0],[1,1],[0,1]]},
              {"id": "mid", "material": "rock", "vertices": [[0.1,1],[1.1,1],[1.1,2],[0.1,2]]},
              {"id": "ell", "material": "rock", "rigid": true, "velocity": [-2, -1, 0.5],
               "vertices": [[1.3,1.2],[2.3,1.2],[2.3,1.5],[1.6,1.5],[1.6,2.2],[1.3,2.2]]},
              {"id": "slider", "material": "rock", "rigid": true, "velocity": [3, 0, 0],
               "vertices": [[3,0],[4,0],[3.5,0.6]]}],
   "output": {"every": 50}})");
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::current_path() / "checkpoint_test" / name;
  fs::remove_all(dir);
  return dir;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The lines of a CSV file after its header, from the first whose first field (t) is
// `first_time` on (all of them when it is empty).
std::vector<std::string> rows_from(const fs::path& file, const std::string& first_time) {
  std::ifstream in(file);
  std::vector<std::string> rows;
  bool started = false;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    started = started || first_time.empty() || line.rfind(first_time + ",", 0) == 0;
    if (started) rows.push_back(line);
  }
  return rows;
}

dyn::RunReport run(const json& document, const fs::path& dir, std::size_t checkpoint_every = 0,
                   const fs::path& restart = {}) {
  const dyn::Scene scene = dyn::parse_scene(document, "busy.json");
  dyn::RunOptions options;
  options.out_dir = dir;
  options.checkpoint_every = checkpoint_every;
  options.restart = restart;
  return dyn::run_scene(scene, options);
}

// The resumed run's tracks and energies, from its first row on, are the reference run's rows
// from the same instant, byte for byte; so are the end energies and the counters.
void check_same_continuation(const fs::path& reference, const dyn::RunReport& whole,
                             const fs::path& resumed, const dyn::RunReport& continued) {
  for (const char* file : {"tracks.csv", "energies.csv"}) {
    const std::vector<std::string> tail = rows_from(resumed / file, "");
    BOOST_TEST_REQUIRE(!tail.empty());
    const std::string first_time = tail.front().substr(0, tail.front().find(','));
    const std::vector<std::string> expected = rows_from(reference / file, first_time);
    BOOST_TEST(tail == expected, file << " differs after the restart at t = " << first_time);
  }
  BOOST_TEST(continued.status == "completed");
  BOOST_TEST(continued.steps == whole.steps);
  BOOST_TEST(continued.final.total() == whole.final.total());
  BOOST_TEST(continued.final.friction_dissipated == whole.final.friction_dissipated);
  BOOST_TEST(continued.final.damping_dissipated == whole.final.damping_dissipated);
  BOOST_TEST(continued.initial.total() == whole.initial.total());
  BOOST_TEST(continued.max_penetration == whole.max_penetration);
  BOOST_TEST(continued.predicates.total_calls() == whole.predicates.total_calls());
  // The pre-solve ran before the checkpoint: the resumed run reports it as the whole run does.
  BOOST_TEST(continued.equilibrium.converged == whole.equilibrium.converged);
  BOOST_TEST(continued.equilibrium.iterations == whole.equilibrium.iterations);
  BOOST_TEST(continued.equilibrium.ratio == whole.equilibrium.ratio);
  BOOST_TEST(continued.equilibrium.unsettled == whole.equilibrium.unsettled);
}

}  // namespace

// A checkpoint every 250 steps of 600 leaves the one of step 500 in the directory; the resumed
// run covers steps 500 to 600.
BOOST_AUTO_TEST_CASE(restart_continues_bit_identically) {
  const fs::path whole_dir = fresh_dir("whole");
  const dyn::RunReport whole = run(busy_scene(), whole_dir, 250);
  BOOST_TEST_REQUIRE(whole.status == "completed");
  BOOST_TEST(whole.equilibrium.ran);  // the stack was settled first: that state is in the file
  BOOST_TEST(whole.equilibrium.converged);
  const json checkpoint = json::parse(read_text(whole_dir / "checkpoint.json"));
  BOOST_TEST(checkpoint.at("steps") == 500);
  BOOST_TEST(!checkpoint.at("engine").at("springs").empty());

  const fs::path resumed_dir = fresh_dir("resumed");
  const dyn::RunReport resumed = run(busy_scene(), resumed_dir, 0, whole_dir / "checkpoint.json");
  BOOST_TEST(resumed.restart_steps == 500u);
  check_same_continuation(whole_dir, whole, resumed_dir, resumed);
  BOOST_TEST(resumed.equilibrium.seconds == whole.equilibrium.seconds);  // the one in the file
  const json summary = json::parse(read_text(resumed_dir / "summary.json"));
  BOOST_TEST(summary.at("restart").at("steps") == 500);
}

// The duration is outside the scene's digest: a run of 150 steps, checkpointed at its end,
// lengthened to the full 600 by a restart, is the full run.
BOOST_AUTO_TEST_CASE(a_run_is_lengthened_from_its_last_checkpoint) {
  json shorter = busy_scene();
  shorter["time"]["duration"] = 0.015;
  shorter["output"]["every"] = 150;
  const fs::path short_dir = fresh_dir("short");
  BOOST_TEST_REQUIRE(run(shorter, short_dir, 150).steps == 150u);
  const fs::path whole_dir = fresh_dir("whole_again");
  const dyn::RunReport whole = run(busy_scene(), whole_dir);
  const fs::path resumed_dir = fresh_dir("lengthened");
  const dyn::RunReport resumed = run(busy_scene(), resumed_dir, 0, short_dir / "checkpoint.json");
  BOOST_TEST(resumed.restart_steps == 150u);
  check_same_continuation(whole_dir, whole, resumed_dir, resumed);
}

// A static analysis carries its relaxation (fictitious velocities, scaled masses) across.
BOOST_AUTO_TEST_CASE(a_static_analysis_restarts_bit_identically) {
  json document = busy_scene();
  document["analysis"] = "static";
  document["static_tolerance"] = 1e-12;  // not reached in 600 steps: every step is compared
  const fs::path whole_dir = fresh_dir("static_whole");
  const dyn::RunReport whole = run(document, whole_dir, 250);
  const fs::path resumed_dir = fresh_dir("static_resumed");
  const dyn::RunReport resumed = run(document, resumed_dir, 0, whole_dir / "checkpoint.json");
  BOOST_TEST(resumed.restart_steps == 500u);
  check_same_continuation(whole_dir, whole, resumed_dir, resumed);
  BOOST_TEST_REQUIRE(!resumed.balance.empty());
  BOOST_TEST(resumed.balance.back().first == whole.balance.back().first);
  BOOST_TEST(resumed.balance.back().second == whole.balance.back().second);
}

namespace {

// The InputError of resuming `document` from `checkpoint` (as JSON), or "" when it resumes.
std::string restart_error(const json& document, const json& checkpoint, const std::string& name) {
  const fs::path dir = fresh_dir(name);
  fs::create_directories(dir);
  std::ofstream(dir / "checkpoint.json") << checkpoint.dump();
  try {
    run(document, dir / "out", 0, dir / "checkpoint.json");
  } catch (const dyn::InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

// A checkpoint of another scene, of another version or with a damaged field is refused with
// the field named.
BOOST_AUTO_TEST_CASE(a_checkpoint_that_does_not_fit_is_refused_by_name) {
  const fs::path dir = fresh_dir("source");
  run(busy_scene(), dir, 100);
  const json good = json::parse(read_text(dir / "checkpoint.json"));

  json stiffer = busy_scene();
  stiffer["contact"]["kn"] = 2e9;
  std::string error = restart_error(stiffer, good, "other_scene");
  BOOST_TEST(contains(error, "scene_digest: written for another scene"), error);

  json relabelled = busy_scene();  // description and output do not count
  relabelled["description"] = "the same physics";
  relabelled["output"]["every"] = 7;
  BOOST_TEST(restart_error(relabelled, good, "relabelled") == "");

  json older = good;
  older["rockcontact"] = "0.0.1";
  error = restart_error(busy_scene(), older, "older");
  BOOST_TEST(contains(error, "rockcontact: written by rockcontact 0.0.1"), error);

  json other_format = good;
  other_format["format"] = "something-else";
  error = restart_error(busy_scene(), other_format, "format");
  BOOST_TEST(contains(error, "format: expected \"rockcontact-checkpoint\""), error);

  json damaged = good;
  damaged["engine"]["blocks"][2].erase("velocity");
  error = restart_error(busy_scene(), damaged, "damaged");
  BOOST_TEST(contains(error, "engine.blocks[2].velocity: missing"), error);

  json not_a_number = good;
  not_a_number["engine"]["contacts"][0]["penetration"] = "deep";
  error = restart_error(busy_scene(), not_a_number, "not_a_number");
  BOOST_TEST(contains(error, "engine.contacts[0].penetration: expected a finite number"), error);
}

// The engine checks that a snapshot fits its blocks: one taken of a simulation with another
// block count, or with a contact naming a block that does not exist, is refused.
BOOST_AUTO_TEST_CASE(the_engine_refuses_a_snapshot_of_other_blocks) {
  const dyn::Scene scene = dyn::parse_scene(busy_scene(), "busy.json");
  const dyn::Dda2d simulation(scene.blocks, scene.law, scene.params);
  dyn::Snapshot fewer = simulation.snapshot();
  fewer.blocks.pop_back();
  BOOST_CHECK_EXCEPTION(dyn::Dda2d(scene.blocks, scene.law, scene.params, fewer),
                        std::invalid_argument, [](const std::invalid_argument& e) {
                          return contains(e.what(), "it holds 4 blocks, the simulation 5");
                        });
  dyn::Snapshot astray = simulation.snapshot();
  BOOST_TEST_REQUIRE(!astray.contacts.empty());
  astray.contacts[0].tp = 9;
  BOOST_CHECK_EXCEPTION(dyn::Dda2d(scene.blocks, scene.law, scene.params, astray),
                        std::invalid_argument, [](const std::invalid_argument& e) {
                          return contains(e.what(), "which are not a pair of this simulation");
                        });
}

BOOST_AUTO_TEST_CASE(checkpoints_need_an_output_directory) {
  dyn::RunOptions options;
  options.checkpoint_every = 10;
  BOOST_CHECK_THROW(dyn::run_scene(dyn::parse_scene(busy_scene(), "busy.json"), options),
                    std::invalid_argument);
}
