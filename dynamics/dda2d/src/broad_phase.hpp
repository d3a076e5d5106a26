#pragma once
// Candidate contact pairs of a 2D block assembly. Internal to rockcontact_dynamics. The engine
// keeps them from step to step in a VerletList (below), which calls the grid only to rebuild.
//
// A uniform grid: the cell is the largest box extent of a movable block (so a movable block
// covers at most 2 x 2 cells), doubled until the grid over the assembly's bounding box has at
// most 4 n + 16 cells (blocks spread far apart, e.g. a long runout, would otherwise ask for a
// huge grid). Every box is entered in the cells it covers by a counting sort, and each cell
// pairs its members; a pair whose boxes share several cells is reported only by the cell that
// holds the lower-left corner of the boxes' intersection, so there is no duplicate to remove.
// Boxes are closed, so touching boxes pair up (touching blocks may overlap by the next step).
// Pairs of two fixed blocks are skipped: they never interact. Cost per call: O(n + cells +
// entries + pairs checked), linear in n for blocks of similar size (a sweep along x was
// O(n sqrt n) on a block assembly stacked in columns: each block swept a whole column). A large
// fixed block is entered in every cell it covers; a movable block much larger than the rest
// makes the cells coarse and the per-cell work quadratic in its members.

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

class UniformGrid {
 public:
  // Replaces `pairs` with the candidate pairs, each as (lower index, higher index), in cell
  // order: a function of the boxes alone, so the same boxes give the same order (no sort: it
  // was a tenth of a step's cost at 1e4 blocks).
  void find_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs);

 private:
  struct Layout {
    double x0 = 0.0, y0 = 0.0, cell = 1.0;  // m
    std::size_t nx = 1, ny = 1;
    std::size_t column(double x) const;
    std::size_t row(double y) const;
  };
  Layout layout(std::span<const BroadPhaseBox> boxes) const;
  void fill(std::span<const BroadPhaseBox> boxes, const Layout& grid);

  std::vector<std::size_t> start_;    // per cell: first entry in members_ (counting sort)
  std::vector<std::size_t> members_;  // box indices, cell by cell
  std::vector<std::size_t> scratch_;  // fill cursor per cell
};

// Every pair (i, j), i < j, with at least one block not fixed, in order: for a handful of
// blocks this is cheaper than any broad phase.
void all_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs);

// Candidate pairs kept from step to step (a Verlet list with a skin). A rebuild inflates every
// box by a margin on each side, verlet_margin_fraction of the largest box extent of a movable
// block, pairs the inflated boxes with the grid and sorts the pairs by (i, j). The list stands
// while every box lies inside its inflated box of the last rebuild: two boxes that overlap then
// lie in two inflated boxes that overlap, so the list holds every pair of overlapping boxes
// (a superset: the caller tests the current boxes). The test compares doubles, so the
// guarantee is exact. Sorted, the pairs of overlapping boxes come out in the same order
// whatever the margin and whenever the rebuilds happened.
class VerletList {
 public:
  // Rebuilds the list when a box left its inflated box or the number of boxes changed; returns
  // whether it did.
  bool update(std::span<const BroadPhaseBox> boxes);
  // Pairs (i, j), i < j, sorted, with at least one block not fixed.
  const std::vector<BlockPair>& pairs() const noexcept { return pairs_; }

 private:
  bool stands(std::span<const BroadPhaseBox> boxes) const;

  UniformGrid grid_;
  std::vector<BroadPhaseBox> reach_;  // the inflated boxes of the last rebuild
  std::vector<BlockPair> pairs_;
};

// The margin of a rebuild, as a fraction of the largest movable box extent: 5 cm on the unit
// blocks of bench/dda_scale, which a block in free fall from rest covers in 0.1 s (10³ steps of
// 10⁻⁴ s). A wider margin rebuilds less often and hands the caller more pairs to test.
inline constexpr double verlet_margin_fraction = 0.05;

}  // namespace rockcontact::dynamics::detail
