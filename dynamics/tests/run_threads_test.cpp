#define BOOST_TEST_MODULE run_threads
// `rockcontact run --threads N` end to end, in every engine: the outputs do not depend on the
// thread count. Each output compared prints its numbers in shortest round-trip form, so a force
// summed in another order on one thread count, a contact assembled out of pair order or a
// friction record lost between steps shows up in its bytes.
//
// 2D DDA (data/scenes/jointed_mass.json): 228 blocks of a jointed rock mass and two boundary
// blocks settling for 300 steps with friction and contact dashpots: 148 to 638 contacts per step,
// about 1 400 candidate pairs, so every parallel pass of the engine (the pair kernel, the block
// updates) runs above its threshold of 64 and splits the work between the threads. tracks.csv
// every 20 steps.
//
// 3D DDA (examples/scenes3d/block_system.json, 0.02 s): 18 blocks cut from a cube on a ground
// slab, 36 steps and 16 step cuts, about 400 constraints: the pairs' detection (in chunks of 4),
// their terms (in chunks of 16) and the constraints' open-close decisions all split between the
// threads. tracks.csv and contacts.csv (every constraint's point, normal, forces and mode).
//
// CDEM (data/scenes/cdem_threads.json): two bars meshed into 6 559 elements, above the 4 096 at
// which the element loops go parallel; the striker meets the target at 1e-4 s and 939 clone
// nodes form in the 400 steps. tracks.csv and events.csv (the exact touch time).

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "run_command.hpp"

using rockcontact::test::quoted;
using rockcontact::test::read_text;
using rockcontact::test::run_command;

namespace {

const std::string cli = quoted(ROCKCONTACT_CLI);
const std::filesystem::path scenes = std::filesystem::path(ROCKCONTACT_DYNAMICS_TESTDATA_DIR) / "scenes";
const std::filesystem::path examples = ROCKCONTACT_EXAMPLES_DIR;

// The `files` the run of `scene` on `threads` threads writes (with the `extra` arguments), in order.
std::vector<std::string> outputs(const std::string& name, const std::filesystem::path& scene, std::size_t threads,
                                 const std::vector<std::string>& files, const std::string& extra = "") {
  const auto dir = rockcontact::test::fresh_directory(name + "_threads_" + std::to_string(threads));
  const std::string command = cli + " run " + quoted(scene) + " --out " + quoted(dir) + " --threads " +
                              std::to_string(threads) + extra + " > /dev/null";
  BOOST_TEST_REQUIRE(run_command(command) == 0, command);
  std::vector<std::string> texts;
  for (const std::string& file : files) texts.push_back(read_text(dir / file));
  return texts;
}

std::size_t lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

BOOST_AUTO_TEST_CASE(dda2d_tracks_are_the_same_bytes_on_one_and_two_threads) {
  const auto scene = scenes / "jointed_mass.json";
  const auto one = outputs("dda2d", scene, 1, {"tracks.csv"});
  const auto two = outputs("dda2d", scene, 2, {"tracks.csv"});
  // 228 blocks at t = 0, every 20 of the 300 steps: 16 rows each, and the header.
  BOOST_TEST(lines(one[0]) == 1 + 16 * 228);
  BOOST_TEST((one == two), "tracks.csv differs between 1 and 2 threads");
}

BOOST_AUTO_TEST_CASE(dda3d_tracks_and_contacts_are_the_same_bytes_on_one_and_two_threads) {
  const auto scene = examples / "scenes3d" / "block_system.json";
  const std::vector<std::string> files{"tracks.csv", "contacts.csv", "summary.json"};
  const auto one = outputs("dda3d", scene, 1, files, " --duration 0.02");
  const auto two = outputs("dda3d", scene, 2, files, " --duration 0.02");
  // The header, then 18 blocks at t = 0, after every 20 accepted steps and at the end (a record
  // of its own unless the steps are a multiple of 20), the steps as summary.json gives them.
  const std::string key = "\"steps\": ";
  const std::size_t at = one[2].find(key);
  BOOST_TEST_REQUIRE(at != std::string::npos);
  const std::size_t steps = std::stoul(one[2].substr(at + key.size()));
  BOOST_TEST(steps >= 20u);
  BOOST_TEST(lines(one[0]) == 1 + 18 * (1 + steps / 20 + (steps % 20 != 0 ? 1 : 0)));
  BOOST_TEST(lines(one[1]) > 1000u);
  BOOST_TEST((one[0] == two[0]), "tracks.csv differs between 1 and 2 threads");
  BOOST_TEST((one[1] == two[1]), "contacts.csv differs between 1 and 2 threads");
}

BOOST_AUTO_TEST_CASE(cdem_tracks_and_events_are_the_same_bytes_on_one_and_two_threads) {
  const auto scene = scenes / "cdem_threads.json";
  const std::vector<std::string> files{"tracks.csv", "events.csv"};
  const auto one = outputs("cdem", scene, 1, files);
  const auto two = outputs("cdem", scene, 2, files);
  // 2 bars at t = 0 and every 20 of the 400 steps: 21 rows each, and the header; one touch.
  BOOST_TEST(lines(one[0]) == 1 + 21 * 2);
  BOOST_TEST(lines(one[1]) == 1 + 1u);
  BOOST_TEST((one[0] == two[0]), "tracks.csv differs between 1 and 2 threads");
  BOOST_TEST((one[1] == two[1]), "events.csv differs between 1 and 2 threads");
}
