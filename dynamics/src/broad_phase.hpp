#pragma once
// Candidate contact pairs of a 2D block assembly. Internal to rockcontact_dynamics.
//
// Sweep and prune on x: blocks sorted by the left end of their axis-aligned bounding box; each
// block is paired with the following ones whose left end does not pass its right end, and the
// pair is kept when the boxes also overlap in y. Boxes are closed, so touching boxes pair up
// (touching blocks may overlap by the next step). The order is kept from call to call, so a
// slowly moving assembly re-sorts a nearly sorted list. Pairs of two fixed blocks are skipped:
// they never interact.

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

namespace rockcontact::dynamics::detail {

struct BroadPhaseBox {
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;  // m
  bool fixed = false;
};

using BlockPair = std::pair<std::size_t, std::size_t>;  // (i, j), i < j

class SweepAndPrune {
 public:
  // Replaces `pairs` with the candidate pairs, sorted, each as (lower index, higher index).
  void find_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs);

 private:
  std::vector<std::size_t> order_;
};

// Every pair (i, j), i < j, with at least one block not fixed, in order: for a handful of
// blocks this is cheaper than any broad phase.
void all_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs);

}  // namespace rockcontact::dynamics::detail
