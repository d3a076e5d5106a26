#define BOOST_TEST_MODULE run_threads
// `rockcontact run --threads N` end to end: the outputs do not depend on the thread count.
//
// The scene (data/scenes/jointed_mass.json) is 228 blocks of a jointed rock mass and two boundary
// blocks settling for 300 steps with friction and contact dashpots: 148 to 638 contacts per step,
// about 1 400 candidate pairs, so every parallel pass of the engine (the pair kernel, the block
// updates) runs above its threshold of 64 and splits the work between the threads. tracks.csv
// prints every tracked block's centroid and velocities in shortest round-trip form every 20
// steps, so a force summed in another order on one thread count, a contact assembled out of
// pair order or a friction record lost between steps shows up in its bytes.

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <string>

#include "run_command.hpp"

using rockcontact::test::quoted;
using rockcontact::test::read_text;
using rockcontact::test::run_command;

namespace {

const std::string cli = quoted(ROCKCONTACT_CLI);
const std::filesystem::path scene =
    std::filesystem::path(ROCKCONTACT_DYNAMICS_TESTDATA_DIR) / "scenes" / "jointed_mass.json";

// The tracks.csv of the scene run on `threads` threads.
std::string tracks(std::size_t threads) {
  const auto dir = rockcontact::test::fresh_directory("run_threads_" + std::to_string(threads));
  const std::string command = cli + " run " + quoted(scene) + " --out " + quoted(dir) +
                              " --threads " + std::to_string(threads) + " > /dev/null";
  BOOST_TEST_REQUIRE(run_command(command) == 0, command);
  return read_text(dir / "tracks.csv");
}

}  // namespace

BOOST_AUTO_TEST_CASE(tracks_are_the_same_bytes_on_one_and_two_threads) {
  const std::string one = tracks(1);
  const std::string two = tracks(2);
  // 228 blocks at t = 0, every 20 of the 300 steps: 16 rows each, and the header.
  BOOST_TEST(std::count(one.begin(), one.end(), '\n') == 1 + 16 * 228);
  BOOST_TEST((one == two), "tracks.csv differs between 1 and 2 threads");
}
