#include "rockcontact/dynamics/equilibrium.hpp"

namespace rockcontact::dynamics {

std::vector<char> supported_blocks(const std::vector<std::vector<std::size_t>>& adjacent,
                                   std::span<const char> fixed, std::span<const char> excluded) {
  std::vector<char> moving(fixed.size(), 0);
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < fixed.size(); ++i) {
    if (fixed[i]) queue.push_back(i);
  }
  for (std::size_t k = 0; k < queue.size(); ++k) {
    for (const std::size_t j : adjacent[queue[k]]) {
      if (fixed[j] || excluded[j] || moving[j]) continue;
      moving[j] = 1;
      queue.push_back(j);
    }
  }
  return moving;
}

}  // namespace rockcontact::dynamics
