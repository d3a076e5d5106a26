#pragma once
// The initial equilibrium every engine runs before its first step, as far as the engines share
// it: the modes a scene chooses, the report, the blocks it settles, and the rounds of the
// automatic mode. Each engine assembles and solves its own system (dda2d.hpp, dda3d.hpp).
//
// A block released at zero contact stretch under gravity is not in equilibrium: its springs
// load from zero, overshoot and, near the friction limit, slide (a block on a slope creeps
// downhill at phi > theta). The pre-solve settles the blocks resting on a support at the start
// (directly or through other resting blocks) into static equilibrium with their contacts
// locked against sliding, so that the run starts with the static contact forces in place.
//
// A scene that can move is a valid scene: blocks without a static state (they topple, slide
// on a frictionless face or are held by nothing) are not an error under the default mode.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rockcontact::dynamics {

// The scene's "initial_equilibrium".
enum class InitialEquilibrium {
  off,        // false: every block starts from its given state
  automatic,  // "auto" (the default): settle what has a static state; the blocks a round of the
              // solve finds without one start from their given state, and are reported
  strict,     // true: a resting block without a static state is an error that names it
};

// What the pre-solve did (every engine's summary.json reports it).
struct Equilibrium {
  bool ran = false;            // some blocks started resting on a support
  std::size_t blocks = 0;      // blocks it settled
  std::size_t iterations = 0;  // iterations of its solve, over every round
  double ratio = 0.0;          // the out-of-balance force ratio it reached
  bool converged = false;      // below the tolerance (automatic may start from a state above it)
  double seconds = 0.0;        // wall time
  // Blocks that rest on a support at the start but have no static state there (automatic):
  // they, and the blocks resting on a support only through them, start from their given state.
  std::vector<std::string> unsettled;
};

// Called after every iteration of the pre-solve with the iterations so far and the ratio the
// last one reached (a progress line's numbers).
using EquilibriumProgress = std::function<void(std::size_t iterations, double ratio)>;

// The blocks connected to a fixed block through `adjacent` (block graph of the pairs resting on
// each other), not through an excluded one: 1 for a movable block so reached, else 0.
std::vector<char> supported_blocks(const std::vector<std::vector<std::size_t>>& adjacent,
                                   std::span<const char> fixed, std::span<const char> excluded);

// What one round of an engine's solve found: empty when it settled the blocks; else the blocks
// it found without a static state and why (a sentence naming the first of them).
struct SettleRound {
  std::vector<std::size_t> unsettled;
  std::string why;
};

// The rounds of the pre-solve. `solve(moving)` settles the blocks marked in `moving` (the
// supported ones, without those excluded so far) or reports, leaving them as they started, the
// blocks it found without a static state. Strict: the first such report is thrown as Error(why).
// Automatic: they are excluded and the rest solved again. Returns the excluded blocks, in the
// order found.
template <class Error, class Solve>
std::vector<std::size_t> settle_in_rounds(InitialEquilibrium mode,
                                          const std::vector<std::vector<std::size_t>>& adjacent,
                                          std::span<const char> fixed, Solve&& solve) {
  std::vector<char> excluded(fixed.size(), 0);
  std::vector<std::size_t> unsettled;
  for (;;) {
    const std::vector<char> moving = supported_blocks(adjacent, fixed, excluded);
    if (std::find(moving.begin(), moving.end(), 1) == moving.end()) return unsettled;
    SettleRound round = solve(moving);
    if (round.unsettled.empty()) return unsettled;
    if (mode == InitialEquilibrium::strict) throw Error(round.why);
    for (const std::size_t i : round.unsettled) {
      if (!excluded[i]) unsettled.push_back(i);
      excluded[i] = 1;
    }
  }
}

// Wall time of a scope, added to a total (the pre-solve's `seconds`).
class WallTimer {
 public:
  explicit WallTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~WallTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  WallTimer(const WallTimer&) = delete;
  WallTimer& operator=(const WallTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rockcontact::dynamics
