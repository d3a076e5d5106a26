#include "broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcontact::dynamics::detail {

std::size_t UniformGrid::Layout::column(double x) const {
  const double c = std::floor((x - x0) / cell);
  return std::min(nx - 1, static_cast<std::size_t>(std::max(0.0, c)));
}

std::size_t UniformGrid::Layout::row(double y) const {
  const double r = std::floor((y - y0) / cell);
  return std::min(ny - 1, static_cast<std::size_t>(std::max(0.0, r)));
}

UniformGrid::Layout UniformGrid::layout(std::span<const BroadPhaseBox> boxes) const {
  Layout grid;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
  grid.x0 = grid.y0 = std::numeric_limits<double>::infinity();
  double extent = 0.0;
  for (const BroadPhaseBox& b : boxes) {
    grid.x0 = std::min(grid.x0, b.xmin);
    grid.y0 = std::min(grid.y0, b.ymin);
    x1 = std::max(x1, b.xmax);
    y1 = std::max(y1, b.ymax);
    if (!b.fixed) extent = std::max({extent, b.xmax - b.xmin, b.ymax - b.ymin});
  }
  const double width = x1 - grid.x0, height = y1 - grid.y0;
  grid.cell = extent > 0.0 ? extent : std::max({width, height, 1.0});
  const double most = 4.0 * static_cast<double>(boxes.size()) + 16.0;
  while ((std::floor(width / grid.cell) + 1.0) * (std::floor(height / grid.cell) + 1.0) > most) {
    grid.cell *= 2.0;
  }
  grid.nx = static_cast<std::size_t>(std::floor(width / grid.cell)) + 1;
  grid.ny = static_cast<std::size_t>(std::floor(height / grid.cell)) + 1;
  return grid;
}

// Counting sort of the (cell, box) entries: start_[c] .. start_[c + 1] are cell c's members.
void UniformGrid::fill(std::span<const BroadPhaseBox> boxes, const Layout& grid) {
  start_.assign(grid.nx * grid.ny + 1, 0);
  const auto for_cells = [&](const BroadPhaseBox& b, auto&& visit) {
    for (std::size_t r = grid.row(b.ymin); r <= grid.row(b.ymax); ++r) {
      for (std::size_t c = grid.column(b.xmin); c <= grid.column(b.xmax); ++c) visit(r * grid.nx + c);
    }
  };
  for (const BroadPhaseBox& b : boxes) for_cells(b, [&](std::size_t cell) { ++start_[cell + 1]; });
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  members_.resize(start_.back());
  std::vector<std::size_t>& next = scratch_;
  next.assign(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for_cells(boxes[i], [&](std::size_t cell) { members_[next[cell]++] = i; });
  }
}

void UniformGrid::find_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs) {
  pairs.clear();
  if (boxes.empty()) return;
  const Layout grid = layout(boxes);
  fill(boxes, grid);
  for (std::size_t cell = 0; cell + 1 < start_.size(); ++cell) {
    for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) {
      const BroadPhaseBox& a = boxes[members_[k]];
      for (std::size_t l = k + 1; l < start_[cell + 1]; ++l) {
        const BroadPhaseBox& b = boxes[members_[l]];
        if ((a.fixed && b.fixed) || b.xmin > a.xmax || a.xmin > b.xmax || b.ymin > a.ymax ||
            a.ymin > b.ymax) {
          continue;
        }
        // Report the pair only in the cell of the intersection's lower-left corner.
        const std::size_t owner = grid.row(std::max(a.ymin, b.ymin)) * grid.nx +
                                  grid.column(std::max(a.xmin, b.xmin));
        if (owner != cell) continue;
        pairs.emplace_back(std::min(members_[k], members_[l]), std::max(members_[k], members_[l]));
      }
    }
  }
}

void all_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs) {
  pairs.clear();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      if (!(boxes[i].fixed && boxes[j].fixed)) pairs.emplace_back(i, j);
    }
  }
}

bool VerletList::stands(std::span<const BroadPhaseBox> boxes) const {
  if (reach_.size() != boxes.size()) return false;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const BroadPhaseBox &b = boxes[i], &r = reach_[i];
    if (b.xmin < r.xmin || b.xmax > r.xmax || b.ymin < r.ymin || b.ymax > r.ymax) return false;
  }
  return true;
}

bool VerletList::update(std::span<const BroadPhaseBox> boxes) {
  if (stands(boxes)) return false;
  double extent = 0.0;
  for (const BroadPhaseBox& b : boxes) {
    if (!b.fixed) extent = std::max({extent, b.xmax - b.xmin, b.ymax - b.ymin});
  }
  const double margin = verlet_margin_fraction * extent;
  reach_.assign(boxes.begin(), boxes.end());
  for (BroadPhaseBox& r : reach_) {
    r.xmin -= margin;
    r.ymin -= margin;
    r.xmax += margin;
    r.ymax += margin;
  }
  grid_.find_pairs(reach_, pairs_);
  std::sort(pairs_.begin(), pairs_.end());
  return true;
}

}  // namespace rockcontact::dynamics::detail
