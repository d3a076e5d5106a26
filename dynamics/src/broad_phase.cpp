#include "broad_phase.hpp"

#include <algorithm>

namespace rockcontact::dynamics::detail {

void SweepAndPrune::find_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs) {
  const auto left_of = [&](std::size_t i, std::size_t j) { return boxes[i].xmin < boxes[j].xmin; };
  if (order_.size() != boxes.size()) {
    order_.resize(boxes.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = i;
    std::sort(order_.begin(), order_.end(), left_of);
  }
  // Insertion sort: linear on the nearly sorted order of the previous call.
  for (std::size_t k = 1; k < order_.size(); ++k) {
    const std::size_t moving = order_[k];
    std::size_t at = k;
    while (at > 0 && left_of(moving, order_[at - 1])) {
      order_[at] = order_[at - 1];
      --at;
    }
    order_[at] = moving;
  }
  pairs.clear();
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const BroadPhaseBox& a = boxes[order_[k]];
    for (std::size_t l = k + 1; l < order_.size(); ++l) {
      const BroadPhaseBox& b = boxes[order_[l]];
      if (b.xmin > a.xmax) break;
      if ((a.fixed && b.fixed) || b.ymin > a.ymax || a.ymin > b.ymax) continue;
      pairs.emplace_back(std::min(order_[k], order_[l]), std::max(order_[k], order_[l]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

void all_pairs(std::span<const BroadPhaseBox> boxes, std::vector<BlockPair>& pairs) {
  pairs.clear();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      if (!(boxes[i].fixed && boxes[j].fixed)) pairs.emplace_back(i, j);
    }
  }
}

}  // namespace rockcontact::dynamics::detail
